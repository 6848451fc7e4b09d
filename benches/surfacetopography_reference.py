"""Reference readings of the height-map fixtures by SurfaceTopography (contact.engineering).

Usage (SurfaceTopography 1.25 and gwyfile from PyPI):

    python benches/surfacetopography_reference.py [--make-fixtures] [--extra DIR]

`--make-fixtures` first writes the generated fixtures of tests/fixtures/maps (Gwyddion .gwy with
the `gwyfile` package, ISO 25178 .x3p and binary .sdf written here by the format's layout),
deterministically (the Mountains .mnt fixtures are written by the Rust test
`write_mnt_fixtures`, run with --ignored). Then every file listed in FILES is read with
SurfaceTopography and
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
    ("nid-small.nid", "Scan forward (Z-Axis)"),
    ("nid-small.nid", "Scan backward (Z-Axis)"),
    ("plu-small.plu", "layer0"),
    ("plu-small.plu", "layer1"),
    ("metropro-small.dat", None),
    ("opd-small.opd", "Raw"),
    ("opd-small.opd", "OPD"),
    ("opdx-small.opdx", None),
    ("opdx-3.opdx", None),
    ("mnt-small.mnt", None),
    ("mnt-masked.mnt", None),
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
    ("nid-1.nid", "Scan forward (Z-Axis)"),
    ("nid-1.nid", "Scan backward (Z-AxisSensor)"),
    ("plu-1.plu", None),
    ("metropro-1.dat", None),
    ("opd-1.opd", None),
    ("mnt-1.mnt", None),
    ("mnt-2.mnt", None),
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
    make_instrument_fixtures()


def make_instrument_fixtures():
    """Small files in the layouts of Nanosurf .nid, Sensofar .plu, Zygo MetroPro .dat, Bruker
    Wyko .opd and Dektak .opdx (the example files are megabytes), each read back by
    SurfaceTopography for reference.json. A generator of its own, so that the fixtures above do
    not change."""
    rng = np.random.default_rng(32)
    nid(os.path.join(MAPS, "nid-small.nid"), rng)
    plu(os.path.join(MAPS, "plu-small.plu"), rng)
    metropro(os.path.join(MAPS, "metropro-small.dat"), rng)
    opd(os.path.join(MAPS, "opd-small.opd"), rng)
    opdx(os.path.join(MAPS, "opdx-small.opdx"), rng)


def nid(path, rng):
    """Nanosurf .nid: two groups (forward, backward); forward holds a deflection (N, int32) and a
    height (m, int32), backward a height (m, uint16, channel index 1); 24 x 16 points."""
    nx, ny = 24, 16
    channels = [
        (0, 0, "Scan forward", "Deflection", "N", 4.8e-6, 32, "Signed"),
        (0, 2, "Scan forward", "Z-Axis", "m", 1.0152e-5, 32, "Signed"),
        (1, 1, "Scan backward", "Z-Axis", "m", 2.5e-6, 16, "Unsigned"),
    ]
    lines = ["[DataSet]", "Version=2", "GroupCount=2", "Gr0-Name=Scan forward", "Gr0-ID=0",
             "Gr0-Count=3", "Gr1-Name=Scan backward", "Gr1-ID=0", "Gr1-Count=2"]
    lines += [f"Gr{g}-Ch{c}=DataSet-{g}:{c}" for g, c, *_ in channels]
    lines += ["", "[DataSet-Info]", "Date=01-01-2026", "Time=00:00:00", "Image size=5µm"]
    blocks = []
    for g, c, frame, quantity, unit, rng_z, bits, sign in channels:
        lines += ["", f"[DataSet-{g}:{c}]", "Version=2", f"Points={nx}", f"Lines={ny}",
                  f"Frame={frame}", "Dim0Name=X*", "Dim0Unit=m", "Dim0Range=5e-06", "Dim0Min=0",
                  "Dim1Name=Y*", "Dim1Unit=m", f"Dim1Range={5e-6 * ny / nx!r}", "Dim1Min=0",
                  f"Dim2Name={quantity}", f"Dim2Unit={unit}", f"Dim2Range={rng_z!r}",
                  f"Dim2Min={-rng_z / 2!r}", "SaveMode=Binary", f"SaveBits={bits}",
                  f"SaveSign={sign}", "SaveOrder=Intel"]
        top = 2 ** (bits - 1)
        if sign == "Signed":
            raw = rng.integers(-top // 4, top // 4, (ny, nx)).astype(f"<i{bits // 8}")
        else:
            raw = rng.integers(0, 2 * top, (ny, nx)).astype(f"<u{bits // 8}")
        blocks.append(raw.tobytes())
    # Two empty lines before the data, as the instrument writes them (SurfaceTopography reads
    # the line after an empty line's two bytes with it).
    text = "\r\n".join(lines) + "\r\n\r\n\r\n"
    with open(path, "wb") as f:
        f.write(text.encode("latin-1") + b"#!" + b"".join(blocks))


def plu(path, rng):
    """Sensofar .plu topography: two layers of 20 x 12 points at 1.66 um, the second with two
    points not measured (1000001)."""
    nx, ny = 20, 12
    header = struct.pack("<128sI256s", b"Thu Jan  1 00:00:00 2026", 1767225600, b"synthetic")
    header += struct.pack("<3I7f", ny, nx, nx, 28.22, 1.66, 1.66, 0.0, 0.0, 1.66, 0.0)
    header += struct.pack("<5I", 3, 3, 0, 14, 3)
    header += struct.pack("<5IdfII", ny, nx, ny, nx, 1, 0.06875, 55.6, 23, 0)
    header += struct.pack("<8BI", 0, 2, 251, 6, 1, 0, 0, 0, 1)
    assert len(header) == 500
    out = [header]
    for k in range(2):
        z = (1000 + 5 * rng.standard_normal((ny, nx))).astype("<f4")
        if k == 1:
            z[2, 3] = z[7, 0] = 1000001.0
        out.append(struct.pack("<2I", ny, nx) + z.tobytes() + struct.pack("<2f", z.min(), z.max()))
    with open(path, "wb") as f:
        f.write(b"".join(out))


def metropro(path, rng):
    """Zygo MetroPro .dat, header format 1 (834 bytes): an intensity block of 4 x 3 points, then
    the phase map of 20 x 14 points (int32, big-endian), sign set, phase resolution 1."""
    nx, ny, ax, ay = 20, 14, 4, 3
    h = bytearray(834)

    def put(at, fmt, *v):
        struct.pack_into(">" + fmt, h, at, *v)

    h[0:4] = b"\x88\x1b\x03\x6f"
    put(4, "HI", 1, 834)
    put(48, "hhHHHhI", 0, 0, ax, ay, 1, 255, 2 * ax * ay)
    put(64, "hhHHI", 0, 0, nx, ny, 4 * nx * ny)
    put(76, "i", 1767225600)
    put(164, "ff", 0.5, 6.328e-7)
    put(176, "f", 1.0)
    put(184, "f", 2e-7)
    put(218, "h", 1)
    put(232, "h", 1)
    intensity = rng.integers(0, 4000, (ay, ax)).astype(">u2").tobytes()
    phase = rng.integers(-20000, 20000, (ny, nx)).astype(">i4").tobytes()
    with open(path, "wb") as f:
        f.write(bytes(h) + intensity + phase)


def opd(path, rng):
    """Bruker Wyko .opd: wavelength, mult, aspect, pixel size, a text block, and two rasters
    ("Raw": f32, "OPD": int16) of 18 x 10 points stored with y fastest."""
    nx, ny = 18, 10
    blocks = [
        ("Wavelength", 7, struct.pack("<f", 632.8)),
        ("Mult", 6, struct.pack("<H", 2)),
        ("Aspect", 7, struct.pack("<f", 1.25)),
        ("Pixel_size", 7, struct.pack("<f", 1.5e-4)),
        ("Title", 5, b"synthetc"),
        ("Raw", 3, struct.pack("<3H", nx, ny, 4) + (40 * rng.standard_normal((nx, ny))).astype("<f4").tobytes()),
        ("Empty", 5, b""),
        ("OPD", 3, struct.pack("<3H", nx, ny, 2) + rng.integers(-3000, 3000, (nx, ny)).astype("<i2").tobytes()),
    ]
    n = len(blocks) + 1
    directory = struct.pack("<16shlH", b"Directory", 1, 24 * n, 0xFFFF)
    for name, kind, data in blocks:
        directory += struct.pack("<16shlH", name.encode(), kind, len(data), 8)
    with open(path, "wb") as f:
        f.write(b"\0\0" + directory + b"".join(d for _, _, d in blocks))


def opdx(path, rng):
    """Bruker Dektak .opdx "Surface Height" map of 22 x 9 points (f32 times a data scale in um)."""
    nx, ny = 22, 9

    def name(s):
        b = s.encode()
        return struct.pack("<I", len(b)) + b

    def varlen(n):
        return struct.pack("<BI", 4, n)

    def item(key, kind, payload):
        return name(key) + bytes([kind]) + payload

    def container(key, items):
        body = b"".join(items) + name("") + b"\x7f" + b"\0\0"
        return item(key, 0x7D, varlen(len(body)) + body)

    def text(key, s):
        b = s.encode()
        return item(key, 0x12, varlen(len(b)) + b)

    def quantity(key, value, unit, symbol):
        body = struct.pack("<d", value) + name(unit) + name(symbol)
        return item(key, 0x13, varlen(len(body)) + body)

    z = (1000 * rng.standard_normal((ny, nx))).astype("<f4")
    matrix = item("Matrix", 0x00, name("Matrix<float>") + struct.pack("<I", 1) + name("Height")
                  + varlen(8 + z.nbytes) + struct.pack("<II", ny, nx) + z.tobytes())
    data = container("2D_Data", [container("Height", [
        item("Dimension1Points", 0x07, struct.pack("<I", ny)),
        item("Dimension2Points", 0x07, struct.pack("<I", nx)),
        quantity("Dimension1Extent", 45.0, "Micrometer", "µm"),
        quantity("Dimension2Extent", 0.11, "Millimeter", "mm"),
        quantity("DataScale", 1.5e-4, "Micrometer", "µm"),
        text("DataKind", "Height"),
        matrix,
    ])])
    meta = container("MetaData", [text("DataKind", "Surface Height"), text("PrimaryData2D", "Height"),
                                  item("Version", 0x06, struct.pack("<i", 3))])
    with open(path, "wb") as f:
        f.write(b"VCA DATA\x01\x00\x00\x55" + meta + data + name("") + b"\x7f")


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
    if t.dim == 1:
        # A line scan: one row (j = 0).
        (nx,) = t.nb_grid_pts
        out["nb_grid_pts"] = [int(nx), 1]
        out["samples"] = [[i % nx, 0, finite_or_none(hf[i % nx] * scale)] for i, _ in SAMPLES]
    if t.dim == 2:
        nx, ny = t.nb_grid_pts
        out["samples"] = [
            [i % nx, j % ny, finite_or_none(hf[i % nx, j % ny] * scale)] for i, j in SAMPLES
        ]
    if missing == 0:
        out["sum"] = float(valid.sum())
        out["rms"] = float(np.sqrt(np.mean((valid - valid.mean()) ** 2)))
    if path.endswith(".mnt"):
        # Mountains documents: the fixed height scale SurfaceTopography applies [m per stored
        # integer], and the RMS of the valid points (the examples have missing points).
        out["mnt_height_scale_m"] = float(reader._height_scale_factor * scale)
        out["rms_valid"] = float(np.sqrt(np.mean((valid - valid.mean()) ** 2)))
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
