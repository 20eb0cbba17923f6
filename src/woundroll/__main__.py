"""``python -m woundroll``: the ``woundroll`` command."""

from woundroll.app.cli import main

main()
