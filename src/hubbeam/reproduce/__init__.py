"""`hubbeam reproduce`: the paper's Secs. 5 and 6 recomputed with both formulations.

plan (which runs) -> runner (runs them, in parallel) -> tables (numbers from the
results, beside the paper's) -> report (figures, report.md, tables.json).
"""
