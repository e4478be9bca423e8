"""Minimal VTK XML writing and reading (no vtk module needed): inline base64 binary arrays with
a UInt64 byte-count header (the layout foamToVTK v1912 writes too), and .pvd collections."""
import base64
import os
import struct
import xml.etree.ElementTree as ET

import numpy as np

_TYPES = {np.dtype("float64"): "Float64", np.dtype("float32"): "Float32", np.dtype("int64"): "Int64",
          np.dtype("int32"): "Int32", np.dtype("uint8"): "UInt8"}
_DTYPES = {"Float64": "<f8", "Float32": "<f4", "Int64": "<i8", "Int32": "<i4", "UInt8": "u1", "UInt64": "<u8",
           "Int8": "i1", "UInt32": "<u4", "Int16": "<i2", "UInt16": "<u2"}


def data_array(name, values, components=1):
    """One <DataArray> element as text, binary (base64 of an 8-byte length header + the data)."""
    a = np.ascontiguousarray(values)
    if a.dtype not in _TYPES:
        a = a.astype(np.float64)
    a = a.astype(a.dtype.newbyteorder("<"), copy=False)
    raw = a.tobytes()
    enc = base64.b64encode(struct.pack("<Q", len(raw)) + raw).decode("ascii")
    nc = f" NumberOfComponents='{components}'" if components != 1 else ""
    return (f"<DataArray type='{_TYPES[a.dtype]}' Name='{xml_escape(name)}'{nc} format='binary'>\n"
            f"{enc}\n</DataArray>\n")


def xml_escape(s):
    return (str(s).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
            .replace("'", "&apos;").replace('"', "&quot;"))


def write_pvd(path, entries):
    """entries: [(time, file relative to the .pvd's folder)], in time order."""
    rows = "".join(f"    <DataSet timestep='{t!r}' group='' part='0' file='{xml_escape(f)}'/>\n" for t, f in entries)
    text = ("<?xml version='1.0'?>\n<VTKFile type='Collection' version='0.1' byte_order='LittleEndian'>\n"
            f"  <Collection>\n{rows}  </Collection>\n</VTKFile>\n")
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def read_pvd(path):
    """[(time, absolute path)] of a .pvd collection."""
    root = ET.parse(path).getroot()
    base = os.path.dirname(os.path.abspath(path))
    return [(float(d.get("timestep")), os.path.join(base, d.get("file"))) for d in root.iter("DataSet")]


def decode_array(el, header="UInt64"):
    """numpy array of a <DataArray> (ascii or inline binary, not compressed); vectors reshaped."""
    dt = np.dtype(_DTYPES[el.get("type")])
    nc = int(el.get("NumberOfComponents", "1"))
    fmt = el.get("format", "ascii")
    txt = (el.text or "").strip()
    if fmt == "ascii":
        a = np.array(txt.split(), dtype=dt)
    elif fmt == "binary":
        raw = base64.b64decode("".join(txt.split()))
        hsize = 8 if header == "UInt64" else 4
        n = struct.unpack("<Q" if hsize == 8 else "<I", raw[:hsize])[0]
        a = np.frombuffer(raw[hsize:hsize + n], dtype=dt)
    else:
        raise ValueError(f"DataArray {el.get('Name')}: format {fmt} not supported")
    return a.reshape(-1, nc) if nc > 1 else a


def read_piece(path):
    """The first Piece of a .vtu/.vtp: dict with points (n, 3), cells (dict of cell arrays by name:
    connectivity, offsets, types for UnstructuredGrid; Verts for PolyData), point_data, cell_data,
    and the declared counts."""
    root = ET.parse(path).getroot()
    header = root.get("header_type", "UInt32")
    piece = root.find(".//Piece")
    out = {"type": root.get("type"), "attrib": dict(piece.attrib), "point_data": {}, "cell_data": {}, "cells": {}}
    pts = piece.find("Points/DataArray")
    out["points"] = decode_array(pts, header) if pts is not None else np.zeros((0, 3))
    for tag, key in (("PointData", "point_data"), ("CellData", "cell_data")):
        sec = piece.find(tag)
        if sec is not None:
            for da in sec.findall("DataArray"):
                out[key][da.get("Name")] = decode_array(da, header)
    for tag in ("Cells", "Verts", "Polys", "Lines"):
        sec = piece.find(tag)
        if sec is not None:
            for da in sec.findall("DataArray"):
                out["cells"][(tag, da.get("Name"))] = decode_array(da, header)
    return out
