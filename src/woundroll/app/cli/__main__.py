"""``python -m woundroll.app.cli``: the ``woundroll`` command."""

from woundroll.app.cli.entry import main

main()
