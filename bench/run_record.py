"""What the bench scripts read from a `corofem run` record (RESULT.json)."""
import math


def ms_per_step(record):
    """Every phase of the record's timings_ms per step, and `step`: the whole step (the run's
    total less its set-up)."""
    timings, steps = record["timings_ms"], record["steps"]
    phases = {k: v / steps for k, v in timings.items() if k not in ("setup", "total")}
    phases["step"] = (timings["total"] - timings.get("setup", 0.0)) / steps
    return phases


def displacement_norm(record):
    """The Euclidean norm of the record's displacements over every vertex and component."""
    return math.sqrt(sum(c * c for u in record["displacement"] for c in u))
