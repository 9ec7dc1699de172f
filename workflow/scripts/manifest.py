"""Reads and checks a batch manifest: a CSV with one dressing per row.

Required columns: id, body, garments, body_units, garment_units; optional: fabrics, quality, up.
`garments` and `fabrics` are separated by ';'. Relative paths are relative to the manifest's folder.

A row that cannot be run (its manifest's header lacks a required column, it has missing cells, an
unknown file, a duplicate or unusable id, bad units, ...) is kept with the reason in `reason`;
every other row gets the dress-a-mesh arguments it runs with. Only a manifest that cannot be read
at all (missing, empty, not CSV, no rows) raises ManifestError.
"""
import csv
import math
import os
import re

REQUIRED = ["id", "body", "garments", "body_units", "garment_units"]
OPTIONAL = ["fabrics", "quality", "up"]
QUALITIES = ["fast", "balanced", "accurate"]
UNITS = ["m", "dm", "cm", "mm"]
AXES = ["+x", "-x", "+y", "-y", "+z", "-z"]
# Names the workflow writes beside the rows' folders in the output folder.
RESERVED_IDS = {"summary.csv", "summary.log", "contact_sheet.png"}
ID_PATTERN = re.compile(r"[A-Za-z0-9_][A-Za-z0-9._-]*")


# A row's id names its folder, beside the workflow's temporary names: well within a file name's 255.
MAX_ID_LENGTH = 200
# Snakemake takes a wildcard ending in text repeated 20 or more times for a cycle and stops the
# whole workflow (its PeriodicityDetector): such an id is refused for its row alone.
PERIODIC_END = re.compile(r"((?P<value>.+)(?P=value){19,99})$")


class ManifestError(Exception):
    pass


class Row:
    def __init__(self, line, id):
        self.line = line  # line number in the manifest (the header is line 1)
        self.id = id
        self.body = ""
        self.garments = []
        self.body_units = ""
        self.garment_units = ""
        self.fabrics = []
        self.quality = ""
        self.up = ""
        self.reason = None  # why the row cannot run; None when it can

    def where(self, manifest):
        label = " (id %s)" % self.id if self.id else ""
        return "%s line %d%s" % (manifest, self.line, label)

    def dress_args(self):
        """The arguments after `dress-a-mesh dress`, output folder excluded."""
        args = [self.body] + self.garments
        args += ["--body-units", self.body_units, "--garment-units", self.garment_units]
        for fabric in self.fabrics:
            args += ["--fabric", fabric]
        if self.up:
            args += ["--up", self.up]
        args += ["--quality", self.quality]
        return args


def _units_ok(value):
    if value in UNITS:
        return True
    try:
        number = float(value)
    except ValueError:
        return False
    return math.isfinite(number) and number > 0


def _split(cell):
    return [part.strip() for part in cell.split(";") if part.strip()]


def _resolve(path, folder):
    path = os.path.expanduser(path)
    return os.path.normpath(path if os.path.isabs(path) else os.path.join(folder, path))


def _check_file(what, path):
    if not os.path.exists(path):
        return "%s file not found: %s" % (what, path)
    if not os.path.isfile(path):
        return "%s is not a regular file: %s" % (what, path)
    if not os.access(path, os.R_OK):
        return "%s file not readable: %s" % (what, path)
    return None


def read(path, default_quality="fast"):
    """Returns (rows, ignored_columns); rows in file order. Raises ManifestError for a manifest that
    cannot be read."""
    if default_quality not in QUALITIES:
        raise ManifestError("quality %r: expected one of %s" % (default_quality, ", ".join(QUALITIES)))
    if not os.path.isfile(path):
        raise ManifestError("manifest not found: %s" % path)
    folder = os.path.dirname(os.path.abspath(path))
    try:
        with open(path, "rb") as f:
            f.read().decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise ManifestError("%s: not UTF-8 text (byte %d: 0x%02x)" % (path, e.start, e.object[e.start]))
    with open(path, newline="", encoding="utf-8-sig") as f:
        reader = csv.reader(f)
        try:
            header = next(reader)
        except StopIteration:
            raise ManifestError("%s: empty file (expected a header: %s)" % (path, ",".join(REQUIRED)))
        except csv.Error as e:
            raise ManifestError("%s line %d: %s" % (path, reader.line_num, e))
        header = [h.strip() for h in header]
        # A header without a required column (or naming one twice) makes every row unrunnable;
        # each row is still listed, with this reason.
        missing = [c for c in REQUIRED if c not in header]
        twice = sorted({h for h in header if header.count(h) > 1})
        header_problem = None
        if missing:
            header_problem = "the manifest's header has no column %s (required: %s)" % (
                ", ".join(missing), ",".join(REQUIRED))
        elif twice:
            header_problem = "the manifest's header names column %s more than once" % ", ".join(twice)
        ignored = [h for h in header if h not in REQUIRED + OPTIONAL]
        rows, first_line_of_id = [], {}
        while True:
            try:
                cells = next(reader)
            except StopIteration:
                break
            except csv.Error as e:
                raise ManifestError("%s line %d: %s" % (path, reader.line_num, e))
            if not any(c.strip() for c in cells):
                continue  # blank line
            line = reader.line_num
            values = dict(zip(header, (c.strip() for c in cells)))
            row = Row(line, values.get("id", ""))
            rows.append(row)
            if header_problem:
                row.reason = header_problem
                continue
            row.reason = _check_row(row, values, cells, header, folder, default_quality)
            if row.id and ID_PATTERN.fullmatch(row.id) and row.id not in RESERVED_IDS:
                if row.id in first_line_of_id:
                    row.reason = "id %s is already used on line %d" % (row.id, first_line_of_id[row.id])
                else:
                    first_line_of_id[row.id] = line
    if not rows:
        raise ManifestError("%s: no rows after the header" % path)
    return rows, ignored


def _check_row(row, values, cells, header, folder, default_quality):
    for name, cell in zip(header, cells):
        if "\0" in cell:
            return "%s holds a NUL byte" % (name or "a column")
    if len(cells) < len(header):
        absent = header[len(cells):]
        return "%d of %d columns: no value for %s" % (len(cells), len(header), ", ".join(absent))
    if len(cells) > len(header):
        return "%d columns where the header has %d" % (len(cells), len(header))
    if not row.id:
        return "the id is empty"
    if not ID_PATTERN.fullmatch(row.id):
        return "id %r is not usable as a folder name (letters, digits, '.', '_', '-'; not starting with '.' or '-')" % row.id
    if len(row.id) > MAX_ID_LENGTH:
        return "id is %d characters long (at most %d: it names the row's folder)" % (len(row.id), MAX_ID_LENGTH)
    if PERIODIC_END.search(row.id):
        return "id %r ends in text repeated 20 or more times, which Snakemake refuses as a wildcard" % row.id
    if row.id in RESERVED_IDS:
        return "id %s is a name the workflow writes in the output folder" % row.id
    for column in REQUIRED[1:]:
        if not values[column]:
            return "%s is empty" % column
    row.body = _resolve(values["body"], folder)
    row.garments = [_resolve(g, folder) for g in _split(values["garments"])]
    if not row.garments:
        return "garments lists no file"
    row.body_units = values["body_units"]
    row.garment_units = values["garment_units"]
    for column in ("body_units", "garment_units"):
        if not _units_ok(values[column]):
            return "%s %r: expected m, dm, cm, mm or a positive number of metres per unit" % (column, values[column])
    row.fabrics = _split(values.get("fabrics", ""))
    if len(row.fabrics) not in (0, 1, len(row.garments)):
        return "fabrics names %d fabrics for %d garments (one for all, or one per garment)" % (
            len(row.fabrics), len(row.garments))
    row.quality = values.get("quality", "") or default_quality
    if row.quality not in QUALITIES:
        return "quality %r: expected one of %s" % (row.quality, ", ".join(QUALITIES))
    row.up = values.get("up", "")
    if row.up and row.up not in AXES:
        return "up %r: expected one of %s" % (row.up, ", ".join(AXES))
    problem = _check_file("body", row.body)
    if problem:
        return problem
    for g in row.garments:
        problem = _check_file("garment", g)
        if problem:
            return problem
    return None
