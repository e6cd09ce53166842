"""The renderer's units, one per part of REPORT.md (see render_report.py for what a unit defines)."""
