"""The FastAPI application of the web page and its server (uvicorn).

No ``from __future__ import annotations``: FastAPI reads the endpoints' annotations at
runtime, and their types are imported inside :func:`create_app`."""

# and their types are imported inside create_app()

from importlib import resources
from typing import Any

from woundroll.app.web.inputs import (
    FORM_FIELDS,
    MAX_CASE_BYTES,
    MAX_READINGS_BYTES,
    InputErrors,
    _cases_dir,
    check_inputs,
    inputs_used,
    readings_from_text,
)
from woundroll.app.web.jobs import JobStore
from woundroll.app.web.payload import _error, unit_system
from woundroll.errors import ConvergenceError, InputError


def _headless_plots() -> None:
    """Draw with the Agg backend: the server renders report figures from worker threads,
    and a GUI backend (the default on a desktop with a display) must only be driven from
    the main thread. The server never shows a window, so nothing is lost."""
    import matplotlib

    matplotlib.use("Agg")


def _bad(exc: InputError | ConvergenceError, status: int = 422) -> Any:
    """The page's error answer: ``{"error": ..., "errors": [...]}`` with ``status``."""
    from fastapi.responses import JSONResponse

    body: dict[str, Any] = {"error": _error(exc)}
    body["errors"] = [_error(e) for e in getattr(exc, "errors", [exc])]
    return JSONResponse(body, status_code=status)


def _request_error(err: dict[str, Any]) -> InputError:
    """One of FastAPI's validation errors as the CLI's one-line error naming the field."""
    loc = [str(p) for p in err.get("loc", ()) if p != "body"]
    typ = err.get("type", "")
    if typ == "json_invalid":
        pos = f" (character {loc[0]})" if loc else ""
        why = (err.get("ctx") or {}).get("error", "")
        return InputError(
            f"the request body is not JSON{pos}{': ' + str(why) if why else ''}; send "
            '{"case": TOML text, "overrides": {...}, "readings": CSV text}',
            "request",
        )
    if typ in ("model_attributes_type", "dict_type") and not loc:
        return InputError(
            'the request body must be a JSON object {"case": ..., "overrides": ...}',
            "request",
        )
    fld = ".".join(loc) if loc else "request"
    if loc and loc[0] == "overrides" and len(loc) > 1:
        fld = loc[1]  # the form field itself
    msg = str(err.get("msg", "invalid request"))
    if typ == "string_too_long":
        limit = MAX_CASE_BYTES if fld == "case" else MAX_READINGS_BYTES
        msg = f"too large: the page takes at most {limit} bytes"
    elif typ == "missing":
        msg = "missing (required)"
    return InputError(msg, fld)


def _install_error_handlers(app: Any) -> None:
    """FastAPI's own validation errors and unknown paths answer in the page's error form."""
    from fastapi.exceptions import RequestValidationError
    from starlette.exceptions import HTTPException as StarletteHTTPException

    async def unprocessable(request: Any, exc: Exception) -> Any:
        # FastAPI's own validation (not JSON, a field too long, a wrong type): one line
        # per field, in the page's {"error": ...} form
        errs = list(getattr(exc, "errors", lambda: [])())
        if not errs:
            errs = [{"loc": (), "msg": str(exc)}]
        mine, seen = [], set()
        for e in errs:
            one = _request_error(e)
            if one.field not in seen:
                seen.add(one.field)
                mine.append(one)
        return _bad(InputErrors(mine))

    async def http_error(request: Any, exc: Any) -> Any:
        # unknown paths and wrong methods answer in the same form as everything else
        what = {404: "no such page or API path", 405: "method not allowed here"}.get(
            exc.status_code, str(exc.detail)
        )
        return _bad(
            InputError(f"{what}: {request.method} {request.url.path}", "request"), exc.status_code
        )

    app.add_exception_handler(RequestValidationError, unprocessable)
    app.add_exception_handler(StarletteHTTPException, http_error)


def _start_job(store: JobStore, req: Any) -> Any:
    """Check a run request (case, overrides, readings) and start its job; the job's id and
    status URL, or the page's error answer (422, or 429 when the server is busy)."""
    try:
        case, errors = check_inputs(req.case, req.overrides)
        readings = None
        if req.readings.strip():
            try:
                if case is not None:
                    readings = readings_from_text(req.readings, case, req.lane_width, req.roll)
                elif len(req.readings.encode("utf-8")) > MAX_READINGS_BYTES:
                    readings_from_text(req.readings, None)  # the size error needs no case
            except InputError as exc:
                errors.append(exc)
        elif req.diagnose:
            errors.append(InputError("give readings to diagnose", "readings"))
        if errors:
            raise InputErrors(errors)
        inputs = inputs_used(req.case, req.overrides, case)
        units = unit_system(next(r["value"] for r in inputs if r["key"] == "winding.tension"))
        job = store.start(case, readings, req.diagnose, inputs, units)
    except InputError as exc:
        return _bad(exc, 429 if exc.field == "run" else 422)
    return {"job": job.id, "status_url": f"/api/jobs/{job.id}"}


def create_app() -> Any:
    """The FastAPI application (``uvicorn woundroll.app.web:create_app --factory``)."""
    from fastapi import FastAPI, Request
    from fastapi.responses import HTMLResponse, PlainTextResponse
    from fastapi.templating import Jinja2Templates
    from pydantic import BaseModel, Field

    from woundroll import __version__
    from woundroll.case import bundled_cases

    _headless_plots()
    app = FastAPI(title="woundroll", version=__version__, docs_url=None, redoc_url=None)
    # Jinja2Templates autoescapes .html templates
    templates = Jinja2Templates(directory=str(resources.files("woundroll.app.web") / "templates"))
    store = JobStore()
    app.state.jobs = store
    _install_error_handlers(app)

    class RunRequest(BaseModel):
        case: str = Field(max_length=MAX_CASE_BYTES * 2)
        overrides: dict[str, str] = Field(default_factory=dict, max_length=len(FORM_FIELDS) + 5)
        readings: str = Field(default="", max_length=MAX_READINGS_BYTES * 2)
        lane_width: str = Field(default="", max_length=40)
        roll: str = Field(default="", max_length=100)
        diagnose: bool = False

    @app.get("/", response_class=HTMLResponse)
    def index(request: Request) -> Any:
        page = {
            "cases": bundled_cases(),
            "fields": FORM_FIELDS,
            "version": __version__,
            "max_case": MAX_CASE_BYTES,
            "max_readings": MAX_READINGS_BYTES,
        }
        return templates.TemplateResponse(request, "index.html", page)

    @app.get("/api/cases/{name}", response_class=PlainTextResponse)
    def case_text(name: str) -> Any:
        if name not in bundled_cases():
            return _bad(InputError(f"no bundled case named {name!r}", "CASE"), 404)
        return (_cases_dir() / f"{name}.toml").read_text(encoding="utf-8")

    @app.post("/api/run")
    def start_run(req: RunRequest) -> Any:
        return _start_job(store, req)

    @app.get("/api/jobs/{job_id}")
    def job_status(job_id: str) -> Any:
        job = store.get(job_id)
        if job is None:
            return _bad(InputError("no such run (finished runs are kept for a while)", "job"), 404)
        return job.status()

    @app.post("/api/jobs/{job_id}/cancel")
    def cancel(job_id: str) -> Any:
        job = store.get(job_id)
        if job is None:
            return _bad(InputError("no such run", "job"), 404)
        job.cancel.set()
        return {"id": job_id, "state": job.state, "cancel_requested": True}

    @app.get("/jobs/{job_id}/report", response_class=HTMLResponse)
    def report(job_id: str) -> Any:
        job = store.get(job_id)
        if job is None or job.result is None:
            return HTMLResponse("<p>No finished run with this id.</p>", status_code=404)
        if job.report is None:
            from woundroll.app.report import build_report

            job.report = build_report(
                job.result, readings=job.readings, diagnosis=job.diagnosis, defects=job.defects
            )
        return HTMLResponse(job.report)

    return app


def serve(host: str = "127.0.0.1", port: int = 8000) -> None:
    """Run the page with uvicorn until interrupted."""
    import uvicorn

    uvicorn.run(create_app(), host=host, port=port, log_level="warning")
