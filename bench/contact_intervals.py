"""The contact intervals of a run's events file, read one way for bench/intervals.sh and
scripts/docs_record.py (docs/output-format.md, "Events")."""
import csv


def contact_intervals(events_csv):
    """[start, end, peak normal force] of each contact interval, in the order the events file
    lists them (the peak is on the release's row; end and peak are None while still open)."""
    out, open_at = [], {}
    with open(events_csv) as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")][1:]
    for r in rows:
        t, kind, ret = float(r[0]), r[2], r[3]
        if kind == "contact_onset" and ret not in open_at:
            open_at[ret] = len(out)
            out.append([t, None, None])
        elif kind == "release" and ret in open_at:
            out[open_at.pop(ret)][1:] = [t, float(r[12])]
    return out
