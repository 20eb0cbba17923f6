"""``python -m woundroll.app.cli``: the ``woundroll`` command."""

from woundroll.app.cli import main

main()
