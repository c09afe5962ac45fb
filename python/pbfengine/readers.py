"""Readers of the files pbfengine writes, into NumPy arrays (NumPy and the standard library only).

- read_frame(path): a dump/text frame (engine/fixes/dump_text.cpp): the particle count N,
  then N lines "x y z vx vy vz" (the original study's format), or, with other fields, the
  same after a line "# NAME ..." naming the columns ("position.0": a vector's first component).
- read_vtu(path): a dump/vtk frame (engine/io/vtu.cpp): a .vtu, little-endian, every array
  appended raw after a UInt64 byte count; or a distributed run's .pvtu and its pieces.
- read_pvd(path): the .pvd collection beside dump/vtk's frames: (time, file) pairs.
- read_thermo(path): the thermo CSV (engine/core/thermo.cpp): "# units: NAME UNIT, ...", a
  row of names, then rows; another such pair of lines wherever pbf.thermo changed the columns.
- frame_paths(pattern): a dump's frames, from its path pattern ("out/frame_*.txt"), in order.

A frame maps each field the dump's `fields` names ("position", "id", "density", ...) to an
array, (N,) or (N, components), in id order: a text frame and a .vtu of the same fields read
alike. Malformed input raises ValueError naming the file and the line or element (a missing
file, FileNotFoundError): nothing is returned half read.
"""
import glob
import os
import stat
import re
import xml.etree.ElementTree as ET

import numpy as np

__all__ = ["Frame", "Thermo", "read_frame", "read_vtu", "read_pvd", "read_thermo", "frame_paths"]


class Frame(dict):
    """Per-particle fields by name (a dict), in the file's order, but len(frame) is the
    particle count. `time` and `step` are None where the file does not record them (neither
    frame format does: read_pvd has the times)."""

    def __init__(self, fields, count, path=None, time=None, step=None):
        super().__init__(fields)
        self.count, self.path, self.time, self.step = count, path, time, step

    def __len__(self):
        return self.count

    def names(self):
        return list(self)

    def __repr__(self):
        return f"Frame({self.path!r}, {self.count} particles, {self.names()})"


class Thermo(dict):
    """Thermo columns by name (a dict), 1-D arrays over the rows, `columns` in the file's
    order, `units` by name; len(thermo) is the number of rows. Where pbf.thermo changed the
    columns mid-file, a column is NaN in the rows written without it."""

    def __init__(self, columns, units, rows, path=None):
        super().__init__(columns)
        self.columns, self.units, self.rows, self.path = list(columns), units, rows, path

    def __len__(self):
        return self.rows

    def __repr__(self):
        return f"Thermo({self.path!r}, {self.rows} rows, {self.columns})"


def _read_bytes(path):
    path = os.fspath(path)
    if not os.path.exists(path):
        raise FileNotFoundError(f"{path}: no such file")
    if os.path.isdir(path):
        raise ValueError(f"{path}: is a directory, not a file")
    if not stat.S_ISREG(os.stat(path).st_mode):  # a FIFO would wait for a writer, a device never end
        raise ValueError(f"{path}: is not a regular file")
    with open(path, "rb") as f:
        return f.read()


def _text_lines(path):
    """The file's lines; every writer ends each line with a newline, so a file that does not
    end with one was cut off."""
    data = _read_bytes(path)
    if not data:
        raise ValueError(f"{path}: empty file")
    text = data.decode("utf-8", "replace")  # a stray byte then fails as a number, on its line
    if not text.endswith("\n"):
        line = text.count("\n") + 1
        raise ValueError(f"{path}:{line}: truncated file: the last line has no end of line")
    return text[:-1].split("\n")


def _number_error(path, numbered, sep=None, column=None):
    """The ValueError for the first value of the (line number, line) pairs that is not a
    number (with `column`: not an integer in that column)."""
    for number, line in numbered:
        for k, token in enumerate(line.split(sep)):
            try:
                float(token) if column is None else int(token) if k == column else None
            except ValueError:
                what = "a number" if column is None else "an integer"
                return ValueError(f"{path}:{number}: column {k + 1}: {token.strip()!r} is not {what}")
    return ValueError(f"{path}: a value is out of range")  # NumPy refused one that Python reads


def _group_components(names):
    """Header columns ("id", "position.0", "position.1", "position.2") as fields:
    [(name, first column, components)]; NAME.0, NAME.1, ... in a row make one vector field."""
    fields, k = [], 0
    while k < len(names):
        m = re.fullmatch(r"(.+)\.0", names[k])
        count = 1
        while m and k + count < len(names) and names[k + count] == f"{m.group(1)}.{count}":
            count += 1
        fields.append((m.group(1) if m and count > 1 else names[k], k, count))
        k += count
    return fields


def read_frame(path):
    """A dump/text frame as a Frame: "position" and "velocity" (N, 3) in the original format,
    else the header's fields; "id" as int64, everything else float64."""
    path = os.fspath(path)
    lines = _text_lines(path)
    first = 1 if lines[0].startswith("#") else 0
    # The original study's format has no header: its columns are position's, then velocity's.
    names = lines[0][1:].split() if first else [f"{name}.{c}" for name in ("position", "velocity") for c in range(3)]
    if first >= len(lines) or not re.fullmatch(r"\s*\d+\s*", lines[first]):
        got = lines[first] if first < len(lines) else "nothing"
        raise ValueError(f"{path}:{first + 1}: expected the particle count, got {got!r}")
    n, body = int(lines[first]), lines[first + 1:]
    if len(body) != n:
        what = "truncated file: " if len(body) < n else ""
        raise ValueError(f"{path}: {what}line {first + 1} says {n} particles, but {len(body)} lines follow")
    fields = _group_components(names)
    if len({f[0] for f in fields}) != len(fields):
        raise ValueError(f"{path}:1: a field is named twice in the header: {' '.join(names)}")
    ncols, tokens = len(names), []
    for i, line in enumerate(body):
        row = line.split()
        if len(row) != ncols:
            raise ValueError(f"{path}:{first + 2 + i}: {len(row)} columns, expected {ncols} ({' '.join(names)})")
        tokens += row
    columns = {}
    for name, k, count in fields:
        try:
            dtype = np.int64 if name == "id" else np.float64
            values = np.array([tokens[k + c::ncols] for c in range(count)], dtype=dtype)
        except (ValueError, OverflowError):
            raise _number_error(path, enumerate(body, first + 2), column=k if name == "id" else None) from None
        columns[name] = values[0] if count == 1 else values.T.copy()
    return Frame(columns, n, path)


_VTK_TYPES = {"Float32": "<f4", "Float64": "<f8", "Int64": "<i8"}  # what dump/vtk declares (engine/io/vtu.hpp)


def _vtk_root(path, text, kind):
    try:
        root = ET.fromstring(text)
    except ET.ParseError as e:
        raise ValueError(f"{path}:{e.position[0]}: not valid XML ({e})") from None
    if root.tag != "VTKFile" or root.get("type") != kind:
        raise ValueError(f"{path}: not a VTK {kind} file (<{root.tag} type={root.get('type')!r}>)")
    return root


def _attribute_int(path, element, name):
    value = element.get(name, "")
    if not value.isdigit():
        raise ValueError(f"{path}: <{element.tag}> needs {name} = a non-negative integer, got {value!r}")
    return int(value)


def read_vtu(path):
    """A dump/vtk frame (.vtu, or a distributed run's .pvtu) as a Frame: "position" (N, 3)
    from the Points, then each PointData array under its Name, with the type the file
    declares; vector arrays (N, k)."""
    path = os.fspath(path)
    if path.endswith(".pvtu"):
        return _read_pvtu(path)
    data = _read_bytes(path)
    tag = data.find(b"<AppendedData")
    gt = data.find(b">", tag)
    if tag < 0 or gt < 0:
        raise ValueError(f"{path}: no <AppendedData> element (truncated, or not written by dump/vtk)")
    # The binary block cannot go through an XML parser: the head is parsed with the
    # AppendedData element closed empty, and the block located by its delimiters.
    root = _vtk_root(path, data[:gt].rstrip(b"/") + b"/></VTKFile>", "UnstructuredGrid")
    expected = {"byte_order": "LittleEndian", "header_type": "UInt64", "compressor": None}
    for name, value in expected.items():
        if root.get(name) != value:
            raise ValueError(f"{path}: <VTKFile> {name}={root.get(name)!r}; dump/vtk writes {value!r}")
    if root.find("AppendedData").get("encoding") != "raw":
        raise ValueError(f"{path}: <AppendedData> encoding is not \"raw\", which dump/vtk writes")
    start = data.find(b"_", gt)
    end = data.rfind(b"</AppendedData>")
    tail = data[end:].split() if end > start >= 0 and not data[gt + 1:start].strip() else None
    if tail != [b"</AppendedData>", b"</VTKFile>"]:
        raise ValueError(f"{path}: truncated file: the appended data do not end with </AppendedData></VTKFile>")
    block = memoryview(data)[start + 1:end]
    pieces = root.findall("UnstructuredGrid/Piece")
    if len(pieces) != 1:
        raise ValueError(f"{path}: {len(pieces)} <Piece> elements in <UnstructuredGrid>, expected 1")
    n = _attribute_int(path, pieces[0], "NumberOfPoints")
    sizes = _block_sizes(path, pieces[0], block)
    points = pieces[0].find("Points/DataArray")
    if points is None:
        raise ValueError(f"{path}: no <Points> with a <DataArray>: the file has no positions")
    fields = {"position": _appended_array(path, points, block, sizes, n, "the Points <DataArray>")}
    if fields["position"].shape != (n, 3):
        components = points.get("NumberOfComponents")
        raise ValueError(f"{path}: the Points <DataArray> has {components} components, expected 3")
    for array in pieces[0].findall("PointData/DataArray"):
        name = array.get("Name")
        if not name or name in fields:
            raise ValueError(f"{path}: a PointData <DataArray> has no Name, or a Name used twice: {name!r}")
        fields[name] = _appended_array(path, array, block, sizes, n, f"<DataArray Name={name!r}>")
    return Frame(fields, n, path)


def _block_sizes(path, piece, block):
    """{offset: bytes} of every array's data. Each is a UInt64 byte count and the bytes, the
    next array's starting where one's ends and the last's at the end of the data (before the
    newline): checking all of them, Cells' too, catches a file cut short anywhere."""
    sizes, at, arrays = {}, 0, []
    for array in piece.iter("DataArray"):
        if array.get("format") != "appended":
            raise ValueError(f"{path}: <DataArray Name={array.get('Name')!r}> has format={array.get('format')!r}; "
                             "dump/vtk writes \"appended\"")
        arrays.append((_attribute_int(path, array, "offset"), array))
    for offset, array in sorted(arrays, key=lambda pair: pair[0]):
        what = f"<DataArray Name={array.get('Name')!r}>"
        if offset != at:
            raise ValueError(f"{path}: {what} starts at offset {offset}, but the data before it end at {at}")
        if at + 8 > len(block):
            raise ValueError(f"{path}: truncated file: {what} starts past the data's end ({len(block)} bytes)")
        sizes[offset] = int(np.frombuffer(block, "<u8", 1, offset)[0])
        at += 8 + sizes[offset]
    if at > len(block):
        raise ValueError(f"{path}: truncated file: the arrays need {at} bytes of data, only {len(block)} are there")
    if bytes(block[at:]).strip():
        raise ValueError(f"{path}: {len(block) - at} bytes of data after the last array's")
    return sizes


def _appended_array(path, array, block, sizes, n, what):
    """One DataArray's values, of the type it declares, checked against NumberOfPoints."""
    dtype = _VTK_TYPES.get(array.get("type"))
    if dtype is None:
        raise ValueError(f"{path}: {what} has unknown type {array.get('type')!r}")
    components = _attribute_int(path, array, "NumberOfComponents") if "NumberOfComponents" in array.attrib else 1
    offset = _attribute_int(path, array, "offset")
    need = n * components * np.dtype(dtype).itemsize
    if sizes[offset] != need:
        raise ValueError(f"{path}: {what} holds {sizes[offset]} bytes, but NumberOfPoints = {n} needs {need}")
    values = np.frombuffer(block, dtype, n * components, offset + 8).astype(dtype[1:])  # a copy, native order
    return values.reshape(n, components) if components > 1 else values


def _read_pvtu(path):
    """A distributed frame: the pieces (one per rank, each in id order) joined, and put in id
    order when the frame has ids, as one process's frame is."""
    root = _vtk_root(path, _read_bytes(path), "PUnstructuredGrid")
    sources = [p.get("Source") for p in root.findall("PUnstructuredGrid/Piece")]
    if not sources or None in sources:
        raise ValueError(f"{path}: <PUnstructuredGrid> has no <Piece Source=...> elements")
    declared = ["position"] + [a.get("Name") for a in root.findall("PUnstructuredGrid/PPointData/PDataArray")]
    frames = [read_vtu(os.path.join(os.path.dirname(path), s)) for s in sources]
    for frame in frames:
        if frame.names() != declared:
            raise ValueError(f"{path}: piece {frame.path} holds {frame.names()}, the .pvtu declares {declared}")
    fields = {name: np.concatenate([f[name] for f in frames]) for name in declared}
    if "id" in fields:
        order = np.argsort(fields["id"], kind="stable")
        fields = {name: values[order] for name, values in fields.items()}
    return Frame(fields, len(fields["position"]), path)


def read_pvd(path, part=0):
    """The collection's frames of `part` (0: the particles; 1, 2, ...: solids' surfaces) as
    [(time, path)], paths joined to the collection's directory, in the file's order."""
    path = os.fspath(path)
    root = _vtk_root(path, _read_bytes(path), "Collection")
    if root.find("Collection") is None:
        raise ValueError(f"{path}: no <Collection> element")
    out = []
    for k, dataset in enumerate(root.findall("Collection/DataSet")):
        try:
            time, file = float(dataset.get("timestep")), dataset.attrib["file"]
            this_part = int(dataset.get("part", "0"))
        except (TypeError, KeyError, ValueError):
            raise ValueError(f"{path}: <DataSet> {k + 1} needs timestep (a number), part and file: "
                             f"{dataset.attrib}") from None
        if this_part == part:
            out.append((time, os.path.join(os.path.dirname(path), file)))
    return out


def read_thermo(path):
    """The thermo CSV as a Thermo: step and particles (thermo.cpp's counts) as int64 where
    every row has them, every other column float64."""
    path = os.fspath(path)
    units, sections, header = {}, [], None  # sections: [names, [(line number, row)]]
    for number, line in enumerate(_text_lines(path), 1):
        if line.startswith("# units:"):  # the header row of names follows it
            units.update(item.strip().partition(" ")[::2] for item in line[len("# units:"):].split(","))
            header = number + 1
        elif line.startswith("#"):
            continue
        elif number == header:
            names = line.split(",")
            if len(set(names)) != len(names) or "" in names:
                raise ValueError(f"{path}:{number}: a column is empty or named twice: {line!r}")
            sections.append((names, []))
        elif not sections:
            raise ValueError(f"{path}:{number}: a row before the header (the '# units:' line and the names)")
        elif line.count(",") + 1 != len(sections[-1][0]):
            names = sections[-1][0]
            got = line.count(",") + 1
            raise ValueError(f"{path}:{number}: {got} values, expected {len(names)} ({','.join(names)})")
        else:
            sections[-1][1].append((number, line))
    if not sections:
        raise ValueError(f"{path}: no header row (the column names after a '# units:' line)")
    columns = list(dict.fromkeys(name for names, _ in sections for name in names))
    parts = {name: [] for name in columns}
    for names, rows in sections:
        try:
            values = np.array([row.split(",") for _, row in rows], dtype=np.float64).reshape(len(rows), len(names))
        except ValueError:
            raise _number_error(path, rows, ",") from None
        for name in columns:
            parts[name].append(values[:, names.index(name)] if name in names else np.full(len(rows), np.nan))
    out = {name: np.concatenate(parts[name]) for name in columns}
    for name in ("step", "particles"):
        if name in out and np.all(out[name] == np.round(out[name])):  # NaN where a row lacks it: not integral
            out[name] = out[name].astype(np.int64)
    return Thermo(out, units, sum(len(rows) for _, rows in sections), path)


def frame_paths(pattern):
    """The files of a dump's path pattern ("out/frame_*.vtu": '*' is the frame number, five
    digits or more), sorted by frame number. A distributed run's .vtk frames are .pvtu files
    (read_pvd lists them)."""
    pattern = os.fspath(pattern)
    if pattern.count("*") != 1:
        raise ValueError(f"the pattern {pattern!r} must contain one '*', as a dump's path does")
    prefix, suffix = pattern.split("*")
    number = re.compile(re.escape(prefix) + r"(\d{5,})" + re.escape(suffix) + r"\Z")
    found = [(int(m.group(1)), p) for p in glob.glob(glob.escape(prefix) + "*" + glob.escape(suffix))
             if (m := number.match(p))]
    return [p for _, p in sorted(found)]
