"""The whole reproduction: plan -> runs -> tables -> report."""

from __future__ import annotations

import os
from pathlib import Path

from hubbeam.reproduce import report, runner, tables
from hubbeam.reproduce.plan import Plan


def reproduce(directory, quick: bool = False, jobs: int | None = None, plan: Plan | None = None,
              progress=None) -> tuple[Path, dict]:
    """Run every case of ``plan`` (default: Plan.quick() or Plan.full()) on ``jobs`` processes
    (default: all cores) and write the report into ``directory``. Returns (report path, tables)."""
    plan = plan or (Plan.quick() if quick else Plan.full())
    jobs = jobs or os.cpu_count() or 1
    outcomes = runner.run_cases(plan.cases(), jobs=jobs, progress=progress)
    result = tables.all_tables(plan, outcomes)
    return report.write(plan, outcomes, result, directory, quick), result
