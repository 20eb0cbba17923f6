"""``woundroll serve [--host 127.0.0.1] [--port 8000]``: the shop-floor web page
(:mod:`woundroll.app.web`). Registered in :mod:`woundroll.app.cli`."""

from __future__ import annotations

from typing import Annotated

import typer

from woundroll.errors import InputError


def serve_cmd(
    port: Annotated[int, typer.Option(help="TCP port.", min=1, max=65535)] = 8000,
    host: Annotated[
        str,
        typer.Option(help="Address to listen on; 127.0.0.1 keeps the page on this machine."),
    ] = "127.0.0.1",
) -> None:
    """Serve the web page: pick or edit a case, paste readings, run, see plots and a report."""
    from woundroll.app.cli.console import fail, out

    try:
        import fastapi  # noqa: F401
        import uvicorn  # noqa: F401

        from woundroll.app.web import serve
    except ImportError as exc:
        fail(InputError(f"the web page needs fastapi and uvicorn ({exc})", "serve"), 2)
    import socket

    try:  # say it in one line before uvicorn would log and exit
        with socket.create_server((host, port)):
            pass
    except OSError as exc:
        fail(InputError(f"cannot listen on {host}:{port}: {exc.strerror or exc}", "--port"), 2)
    out.print(f"woundroll web page on http://{host}:{port}/ (Ctrl-C stops it)")
    serve(host, port)


def register(app: typer.Typer) -> None:
    """Add ``serve`` to the ``woundroll`` app."""
    app.command("serve")(serve_cmd)
