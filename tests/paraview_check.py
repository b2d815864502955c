"""pvpython check: ParaView's XDMF reader loads RUN.xmf; at the last frame the particles have N points and the named
point fields, (triangles=T) the membranes are a surface of T triangles over the same points, and (walls=P,C) the
walls are a block of P points and C triangles with a cell field "wall", which moves between the first and the last
time (a press: the punch comes down).
usage: pvpython paraview_check.py RUN.xmf N FIELD... [triangles=T] [walls=P,C]"""
import sys

from paraview.simple import UpdatePipeline, XDMFReader

path, n = sys.argv[1], int(sys.argv[2])
fields = [a for a in sys.argv[3:] if not a.startswith(("triangles=", "walls="))]
tri = [int(a.split("=")[1]) for a in sys.argv[3:] if a.startswith("triangles=")]
walls = [[int(v) for v in a.split("=")[1].split(",")] for a in sys.argv[3:] if a.startswith("walls=")]
reader = XDMFReader(FileNames=[path])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues)


def load(time):
    """The grids at this time, by name"""
    UpdatePipeline(time=time, proxy=reader)
    data = reader.GetClientSideObject().GetOutputDataObject(0)
    blocks = {}
    if hasattr(data, "GetNumberOfBlocks"):  # several grids: a multiblock of them by name
        for i in range(data.GetNumberOfBlocks()):
            blocks[data.GetMetaData(i).Get(data.NAME())] = data.GetBlock(i)
    else:  # the particles alone
        blocks["particles"] = data
    return blocks


def points(block):
    return [block.GetPoint(i) for i in range(block.GetNumberOfPoints())]


first = None
if walls:  # the walls' points at the first time, before the last time's replace the reader's output
    w0 = load(times[0]).get("walls")
    first = points(w0) if w0 is not None else None
blocks = load(times[-1])
problems = []
p = blocks.get("particles")
if p is None:
    sys.exit(f"paraview_check: {path}: no particles grid (grids: {sorted(blocks)})")
names = [p.GetPointData().GetArrayName(k) for k in range(p.GetPointData().GetNumberOfArrays())]
print(f"paraview_check: {path}: {len(times)} times, {p.GetNumberOfPoints()} points, fields {sorted(names)}")
if p.GetNumberOfPoints() != n:
    problems.append(f"{p.GetNumberOfPoints()} points, expected {n}")
# the geometry is the position field; every other field is a point array
for f in fields:
    if f != "position" and f not in names:
        problems.append(f"field {f} missing")
if len(times) < 2:
    problems.append("fewer than 2 time steps")
if tri:
    m = blocks.get("membranes")
    if m is None:
        problems.append("no membranes grid")
    else:
        types = {m.GetCellType(c) for c in range(m.GetNumberOfCells())}
        print(f"paraview_check: membranes: {m.GetNumberOfCells()} cells of VTK types {sorted(types)} over "
              f"{m.GetNumberOfPoints()} points")
        if m.GetNumberOfCells() != tri[0] or types != {5} or m.GetNumberOfPoints() != n:
            problems.append(f"membranes: {m.GetNumberOfCells()} cells of types {types}, expected {tri[0]} triangles")
if walls:
    w = blocks.get("walls")
    if w is None or first is None:
        problems.append(f"no walls grid (grids: {sorted(blocks)})")
    else:
        types = {w.GetCellType(c) for c in range(w.GetNumberOfCells())}
        wall_ids = w.GetCellData().GetArray("wall")
        last = points(w)
        moved = sum(a != b for a, b in zip(first, last))
        print(f"paraview_check: walls: {w.GetNumberOfCells()} cells of VTK types {sorted(types)} over "
              f"{w.GetNumberOfPoints()} points, {moved} of them moved from t = {times[0]} to {times[-1]}")
        if [w.GetNumberOfPoints(), w.GetNumberOfCells()] != walls[0] or types != {5}:
            problems.append(f"walls: {w.GetNumberOfPoints()} points, {w.GetNumberOfCells()} cells of types {types}, "
                            f"expected {walls[0][0]} points and {walls[0][1]} triangles")
        if wall_ids is None:
            problems.append("walls: no cell field 'wall'")
        if len(first) != len(last) or moved == 0:
            problems.append("walls: no point moved between the first and the last time")
if problems:
    sys.exit("paraview_check: " + "; ".join(problems))
print("paraview_check: ok")
