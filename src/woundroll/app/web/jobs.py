"""Background runs of the web page: a job per run, its stages and progress, cancelling, and
the store that keeps at most MAX_RUNNING running and MAX_JOBS kept."""

# and their types are imported inside create_app()

import threading
import time
import uuid
from dataclasses import dataclass, field
from typing import Any

from woundroll.app.web.inputs import MAX_JOBS, MAX_RUNNING
from woundroll.app.web.payload import _error, _measured, profile_check_payload, result_payload
from woundroll.errors import ConvergenceError, InputError

#: What the page says for the models' progress stages.
STAGE_LABELS = {
    "winding": "winding the roll",
    "contact": "contact model (roll spring under the head)",
    "impact": "impact of the striker",
    "foundation": "foundation (CMD profile)",
    "dynamic": "dynamic contact",
    "diagnosis: forward curve": "diagnosis: full forward runs over tension",
    "diagnosis: material": "diagnosis: material sensitivity",
}


class Cancelled(Exception):
    """Raised inside a run's progress callback when its job was cancelled."""


@dataclass
class Job:
    id: str
    state: str = "queued"  # queued, running, done, error, cancelled
    stage: str = ""
    fraction: float = 0.0
    #: True while work goes on that reports no fraction (the page shows a moving bar)
    indeterminate: bool = False
    inputs: list[dict[str, Any]] | None = None
    units: str | None = None
    started: float = field(default_factory=time.time)
    cancel: threading.Event = field(default_factory=threading.Event)
    result: Any = None
    readings: Any = None
    diagnose: bool = False
    diagnosis: Any = None
    defects: Any = None
    payload: dict[str, Any] | None = None
    error: dict[str, Any] | None = None
    report: str | None = None

    def status(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "id": self.id,
            "state": self.state,
            "stage": self.stage,
            "fraction": None if self.indeterminate else round(self.fraction, 4),
            "indeterminate": self.indeterminate,
            "elapsed_s": round(time.time() - self.started, 2),
        }
        if self.state == "done":
            out["result"] = self.payload
            out["report_url"] = f"/jobs/{self.id}/report"
        if self.error is not None:
            out["error"] = self.error
        return out


class JobStore:
    """Background runs in threads; progress, cancellation, a bounded history."""

    def __init__(self) -> None:
        self.jobs: dict[str, Job] = {}
        self.lock = threading.Lock()

    def running(self) -> int:
        return sum(j.state in ("queued", "running") for j in self.jobs.values())

    def start(
        self,
        case: Any,
        readings: Any,
        diagnose: bool = False,
        inputs: list[dict[str, Any]] | None = None,
        units: str | None = None,
    ) -> Job:
        with self.lock:
            if self.running() >= MAX_RUNNING:
                raise InputError(
                    f"the server is busy ({MAX_RUNNING} runs going): wait or cancel one", "run"
                )
            job = Job(
                uuid.uuid4().hex[:12],
                readings=readings,
                diagnose=diagnose,
                inputs=inputs,
                units=units,
            )
            self.jobs[job.id] = job
            done = [k for k, j in self.jobs.items() if j.state not in ("queued", "running")]
            for k in done[: max(0, len(self.jobs) - MAX_JOBS)]:
                del self.jobs[k]
        threading.Thread(target=self._run, args=(job, case), daemon=True).start()
        return job

    def get(self, job_id: str) -> Job | None:
        return self.jobs.get(job_id)

    def _run(self, job: Job, case: Any) -> None:
        from woundroll.pipeline import run

        def progress(stage: str, fraction: float, after: str = "working on the next step") -> None:
            if job.cancel.is_set():
                raise Cancelled
            label = STAGE_LABELS.get(stage, stage)
            if fraction >= 1.0:
                # the stage is done but the job is not: say what runs now, claim no per cent
                job.stage, job.fraction, job.indeterminate = f"{label} done; {after}", 1.0, True
            else:
                job.stage, job.fraction, job.indeterminate = label, float(fraction), False

        def between(stage: str) -> None:
            if job.cancel.is_set():
                raise Cancelled
            job.stage, job.indeterminate = stage, True

        job.state = "running"
        try:
            from woundroll.assess.defects import defect_report

            result = run(case, progress=progress)
            between("comparing and summing up")
            measured = _measured(job.readings)
            if measured is not None and result.profile is not None:
                from dataclasses import replace

                result = replace(result, profile=result.profile.compare(measured))
            if job.diagnose and job.readings is not None:
                from woundroll.inverse.diagnosis import diagnose

                between("diagnosis: starting the forward runs over tension")

                def diag_progress(stage: str, fraction: float) -> None:
                    progress(
                        f"diagnosis: {stage}",
                        fraction,
                        "diagnosis: checking the result with a full forward run",
                    )

                job.diagnosis = diagnose(case, job.readings, progress=diag_progress)
            between("defect risk and summary")
            job.defects = defect_report(case, job.diagnosis, winding=result.winding)
            job.result = result
            job.payload = result_payload(
                result, measured, job.diagnosis, job.defects, job.inputs, job.units
            )
            job.payload["profile_check"] = profile_check_payload(job.readings, job.units)
            job.stage, job.fraction, job.indeterminate = "", 1.0, False
            job.state = "done"
        except Cancelled:
            job.state = "cancelled"
        except (InputError, ConvergenceError) as exc:
            job.error = _error(exc)
            job.state = "error"
        except Exception as exc:  # the server keeps serving; the page shows what happened
            job.error = {"field": "run", "message": f"{type(exc).__name__}: {exc}"}
            job.error["line"] = f"run: {job.error['message']}"
            job.state = "error"
