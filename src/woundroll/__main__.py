"""``python -m woundroll``: the ``woundroll`` command."""

from woundroll.app.cli.entry import main

main()
