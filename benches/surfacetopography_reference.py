"""Reference readings of the height-map fixtures by SurfaceTopography (contact.engineering).

Usage (SurfaceTopography 1.25 and gwyfile from PyPI):

    python benches/surfacetopography_reference.py [--make-fixtures] [--extra DIR]

`--make-fixtures` first writes the generated fixtures of tests/fixtures/maps (Gwyddion .gwy with
the `gwyfile` package, ISO 25178 .x3p and binary .sdf written here by the format's layout),
deterministically. Then every file listed in FILES is read with SurfaceTopography and
tests/fixtures/maps/reference.json is written: for each file and channel, the grid (nx, ny),
the physical size and unit SurfaceTopography reports and the same in metres, a few heights
(x index i, y index j) in metres, their sum and the RMS height about the mean (no detrending),
and the count of missing (masked) points. `--extra DIR` adds the files of DIR listed in EXTRA
(example files too large to commit) to a second file, reference-extra.json in DIR.
"""

import hashlib
import json
import os
import struct
import sys
import zipfile

import numpy as np
import SurfaceTopography
from SurfaceTopography import open_topography
from SurfaceTopography.Support.UnitConversion import get_unit_conversion_factor

HERE = os.path.dirname(os.path.abspath(__file__))
MAPS = os.path.join(HERE, "..", "tests", "fixtures", "maps")

# (file, channel name or None for SurfaceTopography's default)
FILES = [
    ("sdf-1.sdf", None),
    ("sdf-binary.sdf", None),
    ("matrix-6.txt", None),
    ("gwyddion-export-english.txt", None),
    ("xyz-1.txt", None),
    ("xyz-2.txt", None),
    ("x3p-f32.x3p", None),
    ("x3p-u16.x3p", None),
    ("gwy-1.gwy", "Height"),
    ("gwy-1.gwy", "Height masked"),
    ("sur-3.sur", None),
    ("10x10-one_channel_without_name.ibw", None),
    ("di-3.di", "ZSensor"),
    ("di-3.di", "Height"),
    ("mi-1.mi", "Topography"),
    ("mi-1.mi", "Deflection"),
    ("al3d-1.al3d", None),
]

EXTRA = [
    ("x3p-2.x3p", None),
    ("sur-2.sur", None),
    ("spot_1-1000nm.ibw", None),
    ("di-1.di", None),
    ("di-2.di", None),
    ("di-4.di", None),
    ("di-5.di", None),
    ("di-6.di", None),
    ("matrix-3.txt", None),
]

SAMPLES = [(0, 0), (1, 0), (0, 1), (-1, -1), (3, 2), (-2, 1)]


def x3p(path, nx, ny, dx, dy, z, dtype, increment=None):
    data = {"F": "<f4", "D": "<f8", "I": "<u2", "L": "<u4"}[dtype]
    raw = np.asarray(z, dtype=data).T.tobytes()  # z[i, j]: x fastest in the file
    md5 = hashlib.md5(raw).hexdigest().upper()
    inc = "" if increment is None else f"<Increment>{increment!r}</Increment>"
    xml = f"""<?xml version="1.0" encoding="UTF-8" standalone="no" ?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2">
  <Record1>
    <Revision>ISO5436 - 2000</Revision>
    <FeatureType>SUR</FeatureType>
    <Axes>
      <CX><AxisType>I</AxisType><DataType>D</DataType><Increment>{dx!r}</Increment><Offset>0</Offset></CX>
      <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>{dy!r}</Increment><Offset>0</Offset></CY>
      <CZ><AxisType>A</AxisType><DataType>{dtype}</DataType>{inc}<Offset>0</Offset></CZ>
    </Axes>
  </Record1>
  <Record2>
    <Date>2026-01-01T00:00:00</Date>
    <Instrument><Manufacturer>unknown</Manufacturer><Model>synthetic</Model><Serial>unknown</Serial><Version>unknown</Version></Instrument>
    <CalibrationDate>2026-01-01T00:00:00</CalibrationDate>
    <ProbingSystem><Type>Software</Type><Identification>reference script</Identification></ProbingSystem>
    <Comment/>
  </Record2>
  <Record3>
    <MatrixDimension><SizeX>{nx}</SizeX><SizeY>{ny}</SizeY><SizeZ>1</SizeZ></MatrixDimension>
    <DataLink><PointDataLink>bindata/data.bin</PointDataLink><MD5ChecksumPointData>{md5}</MD5ChecksumPointData></DataLink>
  </Record3>
  <Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4>
</p:ISO5436_2>
"""
    info = zipfile.ZipInfo("main.xml", date_time=(2026, 1, 1, 0, 0, 0))
    binfo = zipfile.ZipInfo("bindata/data.bin", date_time=(2026, 1, 1, 0, 0, 0))
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED) as f:
        f.writestr(info, xml.encode(), compress_type=zipfile.ZIP_DEFLATED)
        f.writestr(binfo, raw, compress_type=zipfile.ZIP_DEFLATED)


def make_fixtures():
    rng = np.random.default_rng(31)
    # X3P, f32 heights [m], 40 x 30 points of 0.25 um.
    z = 1e-7 * rng.standard_normal((40, 30))
    x3p(os.path.join(MAPS, "x3p-f32.x3p"), 40, 30, 2.5e-7, 2.5e-7, z, "F")
    # X3P, u16 heights with a z increment of 1 nm, 24 x 20 points, rectangular pixels.
    z = rng.integers(0, 4000, (24, 20))
    x3p(os.path.join(MAPS, "x3p-u16.x3p"), 24, 20, 1e-6, 2e-6, z, "I", increment=1e-9)
    # Binary SDF, int16 heights, Zscale 2 nm, 16 x 12 points.
    nx, ny = 16, 12
    zi = rng.integers(-3000, 3000, (ny, nx)).astype("<i2")
    header = struct.pack(
        "<8s10s12s12sHHddddbbb", b"bISO-1.0", b"synthetic", b"010120260000", b"010120260000",
        nx, ny, 5e-7, 5e-7, 2e-9, 1e-9, 0, 5, 0,
    )
    with open(os.path.join(MAPS, "sdf-binary.sdf"), "wb") as f:
        f.write(header + zi.tobytes())
    # Gwyddion .gwy: a height channel, a phase channel, and a height channel with a mask.
    from gwyfile.objects import GwyContainer, GwyDataField, GwySIUnit

    c = GwyContainer()
    h = 2e-8 * rng.standard_normal((32, 48))  # rows are y
    c["/0/data"] = GwyDataField(h, xreal=5e-6, yreal=5e-6 * 32 / 48,
                                si_unit_xy=GwySIUnit(unitstr="m"), si_unit_z=GwySIUnit(unitstr="m"))
    c["/0/data/title"] = "Height"
    c["/1/data"] = GwyDataField(rng.standard_normal((32, 48)), xreal=5e-6, yreal=5e-6 * 32 / 48,
                                si_unit_xy=GwySIUnit(unitstr="m"), si_unit_z=GwySIUnit(unitstr="deg"))
    c["/1/data/title"] = "Phase"
    c["/2/data"] = GwyDataField(h[:16, :20].copy(), xreal=2e-6, yreal=1.6e-6,
                                si_unit_xy=GwySIUnit(unitstr="m"), si_unit_z=GwySIUnit(unitstr="m"))
    c["/2/data/title"] = "Height masked"
    mask = np.zeros((16, 20))
    mask[3, 5] = mask[3, 6] = mask[10, 0] = 1.0
    c["/2/mask"] = GwyDataField(mask, xreal=2e-6, yreal=1.6e-6)
    c.tofile(os.path.join(MAPS, "gwy-1.gwy"))


def factor(unit):
    if unit is None:
        return None
    try:
        return get_unit_conversion_factor(unit, "m")
    except Exception:
        return None


def finite_or_none(v):
    """A height for JSON: None for a missing point."""
    return float(v) if np.isfinite(v) else None


def reference(path, channel):
    reader = open_topography(path)
    names = [c.name for c in reader.channels]
    index = None if channel is None else names.index(channel)
    t = reader.topography(channel_index=index)
    name = reader.channels[index or 0].name if channel is None else channel
    h = t.heights()
    missing = int(np.ma.count_masked(h)) if np.ma.isMaskedArray(h) else int(np.isnan(h).sum())
    f = factor(t.unit)
    scale = 1.0 if f is None else f
    hf = np.ma.filled(h.astype(float), np.nan) if np.ma.isMaskedArray(h) else np.asarray(h, float)
    valid = hf[np.isfinite(hf)] * scale
    out = {
        "file": os.path.basename(path),
        "channel": name,
        "channels": names,
        "dim": t.dim,
        "nb_grid_pts": [int(n) for n in t.nb_grid_pts],
        "physical_sizes": None if t.physical_sizes is None else [float(s) for s in t.physical_sizes],
        "unit": t.unit,
        "metres_per_unit": f,
        "physical_sizes_m": None
        if (t.physical_sizes is None or f is None)
        else [float(s) * f for s in t.physical_sizes],
        "missing": missing,
    }
    if t.dim == 2:
        nx, ny = t.nb_grid_pts
        out["samples"] = [
            [i % nx, j % ny, finite_or_none(hf[i % nx, j % ny] * scale)] for i, j in SAMPLES
        ]
        if missing == 0:
            out["sum"] = float(valid.sum())
            out["rms"] = float(np.sqrt(np.mean((valid - valid.mean()) ** 2)))
    return out


def main():
    args = sys.argv[1:]
    if "--make-fixtures" in args:
        make_fixtures()
    refs = [reference(os.path.join(MAPS, f), c) for f, c in FILES]
    doc = {"surfacetopography": SurfaceTopography.__version__, "maps": refs}
    with open(os.path.join(MAPS, "reference.json"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    if "--extra" in args:
        d = args[args.index("--extra") + 1]
        refs = []
        for f, c in EXTRA:
            p = os.path.join(d, f)
            if os.path.exists(p):
                refs.append(reference(p, c))
        with open(os.path.join(d, "reference-extra.json"), "w") as f:
            json.dump({"surfacetopography": SurfaceTopography.__version__, "maps": refs}, f, indent=1)


if __name__ == "__main__":
    main()
