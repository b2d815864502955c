"""pvpython check: ParaView's XDMF reader loads RUN.xmf; the last frame has N points and the named point fields.
usage: pvpython paraview_check.py RUN.xmf N FIELD..."""
import sys

from paraview.simple import UpdatePipeline, XDMFReader

path, n, fields = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
reader = XDMFReader(FileNames=[path])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues)
UpdatePipeline(time=times[-1], proxy=reader)
info = reader.GetDataInformation()
names = [reader.PointData.GetArray(i).Name for i in range(len(reader.PointData))]
print(f"paraview_check: {path}: {len(times)} times, {info.GetNumberOfPoints()} points, fields {names}")
problems = []
if info.GetNumberOfPoints() != n:
    problems.append(f"{info.GetNumberOfPoints()} points, expected {n}")
# the geometry is the position field; every other field is a point array
for f in fields:
    if f != "position" and f not in names:
        problems.append(f"field {f} missing")
if len(times) < 2:
    problems.append("fewer than 2 time steps")
if problems:
    sys.exit("paraview_check: " + "; ".join(problems))
print("paraview_check: ok")
