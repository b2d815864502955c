#!/usr/bin/python3
"""Checks an XDMF file written by dem: every HDF dataset it names exists with the dimensions the XDMF states.
usage: xdmf_check.py RUN.xmf   (exit 0 when consistent)"""
import os
import sys
import xml.etree.ElementTree as ET

import h5py

xmf = sys.argv[1]
root = ET.parse(xmf).getroot()
folder = os.path.dirname(xmf)
files = {}
checked = 0
for item in root.iter("DataItem"):
    if item.get("Format") != "HDF":
        continue
    fname, path = item.text.strip().split(":", 1)
    f = files.setdefault(fname, h5py.File(os.path.join(folder, fname), "r"))
    dims = tuple(int(v) for v in item.get("Dimensions").split())
    if path not in f:
        sys.exit(f"{xmf}: {path} is not in {fname}")
    if f[path].shape != dims:
        sys.exit(f"{xmf}: {path} has shape {f[path].shape}, the XDMF says {dims}")
    checked += 1
frames = len([g for g in root.iter("Grid") if g.get("GridType") == "Uniform"])
if frames == 0 or checked == 0:
    sys.exit(f"{xmf}: no frames")
print(f"{xmf}: {frames} frames, {checked} data items consistent")
