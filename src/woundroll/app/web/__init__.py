"""The shop-floor web page: ``woundroll serve [--host 127.0.0.1] [--port 8000]``.

FastAPI (request validation, JSON endpoints, a test client) with Jinja2 templates, served
by uvicorn. One page: pick a bundled case or edit its TOML, set the common inputs in a
form with units, paste or upload readings across the roll, press run; a background job
runs :func:`woundroll.pipeline.run` and the page polls its progress (cancellable), then
shows the stresses, the predicted (and measured) profile, the headline numbers and a link
to the HTML report (:mod:`woundroll.app.report`).

Safety (the page may be opened by anyone who can reach the port; it listens on 127.0.0.1
unless told otherwise):

* it never takes a file path: ``winding.thickness_profile``, ``profile.measured`` and
  ``web.radial_modulus.file`` may only name the files the bundled cases use
  (:data:`BUNDLED_FILE_REFS`); readings are pasted or uploaded as text, never opened from a
  path;
* it never takes code: the case is TOML parsed by :mod:`tomllib`, readings are CSV text,
  every value goes through the same validation as the CLI;
* a case is at most :data:`MAX_CASE_BYTES`, readings at most :data:`MAX_READINGS_BYTES`;
  at most :data:`MAX_RUNNING` runs at a time and :data:`MAX_JOBS` kept;
* bad input answers 422 with the CLI's one-line message (``field: message``) and the
  offending field, which the page shows beside that field; the server keeps serving.
"""

from woundroll.app.web.inputs import (
    BUNDLED_FILE_REFS,
    MAX_CASE_BYTES,
    MAX_JOBS,
    MAX_READINGS_BYTES,
    MAX_RUNNING,
    InputErrors,
    case_from_text,
    check_inputs,
    inputs_used,
    readings_from_text,
)
from woundroll.app.web.jobs import Job, JobStore
from woundroll.app.web.payload import profile_check_payload, result_payload, unit_system
from woundroll.app.web.server import create_app, serve

__all__ = [
    "BUNDLED_FILE_REFS",
    "MAX_CASE_BYTES",
    "MAX_JOBS",
    "MAX_READINGS_BYTES",
    "MAX_RUNNING",
    "InputErrors",
    "Job",
    "JobStore",
    "case_from_text",
    "check_inputs",
    "create_app",
    "inputs_used",
    "profile_check_payload",
    "readings_from_text",
    "result_payload",
    "serve",
    "unit_system",
]
