"""The results CSV: exact floats (repr round-trips), resume (indices already written), appends.

A row is written as one line and flushed with its chunk; a last line cut short (a killed run)
is dropped on resume, so every line in the file is a whole row.
"""
import csv
import io
import os


class ResultsError(ValueError):
    """A results file that cannot be resumed; str() names the file and the problem."""


def format_value(value):
    """A cell: floats by repr (the shortest text that reads back to the same double)."""
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def line(values):
    """One CSV line (with its newline) of `values`."""
    out = io.StringIO()
    csv.writer(out, lineterminator="\n").writerow([format_value(v) for v in values])
    return out.getvalue()


def done_indices(path, columns):
    """Indices already in results file `path` (an empty set when it does not exist or is empty).

    Its header must be `columns`; a last line without its newline is cut off the file.
    """
    if not os.path.exists(path) or os.path.getsize(path) == 0:
        return set()
    with open(path, "rb+") as f:
        data = f.read()
        if not data.endswith(b"\n"):
            cut = data.rfind(b"\n") + 1
            f.truncate(cut)
            data = data[:cut]
    lines = data.decode("utf-8").splitlines()
    if not lines:
        return set()
    header = next(csv.reader([lines[0]]))
    if header != columns:
        raise ResultsError("%s: its columns are not this scenario's (another scenario or model?); "
                           "write to a new file" % path)
    done = set()
    for n, text in enumerate(lines[1:], 2):
        cells = next(csv.reader([text]), [])
        try:
            done.add(int(cells[0]))
        except (ValueError, IndexError):
            raise ResultsError("%s line %d: no run index in the first column" % (path, n))
    return done


class Writer:
    """Appends rows to a results file, writing the header first when the file is new."""

    def __init__(self, path, columns):
        self.columns = columns
        new = not os.path.exists(path) or os.path.getsize(path) == 0
        self.file = open(path, "a", newline="")
        if new:
            self.file.write(line(columns))
            self.file.flush()

    def write(self, rows):
        """Appends row dicts (keys = columns) and flushes."""
        self.file.write("".join(line([r[c] for c in self.columns]) for r in rows))
        self.file.flush()

    def close(self):
        """Closes the file."""
        self.file.close()
