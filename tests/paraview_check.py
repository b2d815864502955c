"""pvpython check: ParaView's XDMF reader loads RUN.xmf; at the last frame the particles have N points and the named
point fields, and (triangles=T) the membranes are a surface of T triangles over the same points.
usage: pvpython paraview_check.py RUN.xmf N FIELD... [triangles=T]"""
import sys

from paraview.simple import UpdatePipeline, XDMFReader

path, n = sys.argv[1], int(sys.argv[2])
fields = [a for a in sys.argv[3:] if not a.startswith("triangles=")]
tri = [int(a.split("=")[1]) for a in sys.argv[3:] if a.startswith("triangles=")]
reader = XDMFReader(FileNames=[path])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues)
UpdatePipeline(time=times[-1], proxy=reader)
data = reader.GetClientSideObject().GetOutputDataObject(0)
blocks = {}
if hasattr(data, "GetNumberOfBlocks"):  # several grids: a multiblock of them by name
    for i in range(data.GetNumberOfBlocks()):
        blocks[data.GetMetaData(i).Get(data.NAME())] = data.GetBlock(i)
else:  # the particles alone
    blocks["particles"] = data
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
if problems:
    sys.exit("paraview_check: " + "; ".join(problems))
print("paraview_check: ok")
