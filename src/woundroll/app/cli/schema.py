"""``woundroll schema [result|diagnosis|...]``: the JSON Schema (draft 2020-12) of a JSON
document the commands write, built from the one description of the keys
(:mod:`woundroll.pipeline.vocabulary`, docs/nomenclature.md). Registered in
:mod:`woundroll.app.cli`."""

from __future__ import annotations

import sys
from typing import Annotated

import typer

from woundroll.errors import InputError
from woundroll.pipeline.vocabulary import DOCUMENTS, json_schema


def schema_cmd(
    document: Annotated[
        str,
        typer.Argument(help=f"The document: {', '.join(DOCUMENTS)}.", metavar="{document}"),
    ] = "result",
) -> None:
    """Print the JSON Schema (draft 2020-12) of a JSON document woundroll writes."""
    from woundroll.app.cli.console import fail
    from woundroll.util.output import strict_json

    if document not in DOCUMENTS:
        fail(
            InputError(f"unknown document {document!r}; one of {', '.join(DOCUMENTS)}", "document"),
            2,
        )
    sys.stdout.write(strict_json(json_schema(document), indent=1) + "\n")


def register(app: typer.Typer) -> None:
    """Add ``schema`` to the ``woundroll`` app."""
    app.command("schema")(schema_cmd)
