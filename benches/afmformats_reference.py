"""Reference readings of the force-distance fixtures by afmformats, for tests/it/readers.rs.

Run with a Python that has afmformats 0.18.7 (and numpy):

    python benches/afmformats_reference.py

Reads every fixture of tests/fixtures/afm/ with ``afmformats.load_data`` (with the metadata
overrides that afmformats' own tests use where a file lacks the spring constant or the
sensitivity, plus a few override cases) and writes tests/fixtures/afm/reference.json: per case
the file, the options (as adhesion's ``--spring-constant`` / ``--sensitivity``), and per curve the
metadata and, per afmformats segment (the ``segment`` column), the sample count and for each
column its sum, min, max and values at 8 fixed indices.
"""
import json
import pathlib
import tempfile
import warnings
import zipfile

import afmformats
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
FIX = ROOT / "tests" / "fixtures" / "afm"

COLUMNS = {
    "force": "force",
    "height (measured)": "height_measured",
    "height (piezo)": "height_piezo",
    "time": "time",
    "tip position": "tip_position",
}

# (file, meta_override) — the overrides of afmformats' tests (tests/test_fmt_*.py) where the file
# lacks the values, and override cases of files that have them.
CASES = [
    ("fmt-afm-workshop-fd_mapping_16_2018-08-01_13.07.zip", {"spring constant": 20, "sensitivity": 0.01e-6}),
    ("fmt-afm-workshop-fd_single_2018-08-01_13.06.09.csv", {"spring constant": 20, "sensitivity": 0.01e-6}),
    ("fmt-afm-workshop-fd_single_2020-02-14_13.41.25.csv", {}),
    ("fmt-afm-workshop-fd_single_2021-01-15.csv", {"spring constant": 20, "sensitivity": 0.01e-6}),
    ("fmt-afm-workshop-fd_single_2021-10-22_14.16.csv", {}),
    ("fmt-chiaro-txt_AEBP1_Indentation_002.zip", {}),
    ("fmt-hdf5-fd_version_0.13.3.h5", {}),
    ("fmt-igor-fd_SiN_FD_plot.ibw", {}),
    ("fmt-igor-fd_U3_3_p10004.ibw", {}),
    ("fmt-jpk-cc_pr14-brain-2021.06.30.jpk-force", {}),
    ("fmt-jpk-cc_pr14-polymergel-2021.06.30.jpk-force", {}),
    ("fmt-jpk-cl_calibration_force-save-2015.02.04-11.25.21.294.jpk-force",
     {"spring constant": 0.05, "sensitivity": 6e-8}),
    ("fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data", {}),
    ("fmt-jpk-fd_flipsign_2015.05.22-15.31.49.352.jpk-force", {}),
    ("fmt-jpk-fd_map-data-reference-points.jpk-force-map", {}),
    ("fmt-jpk-fd_map0d_extracted.jpk-force-map", {}),
    ("fmt-jpk-fd_map2x2_extracted.jpk-force-map", {}),
    ("fmt-jpk-fd_qi-data-2021.04.13.jpk-qi-series", {}),
    ("fmt-jpk-fd_single-modified_2023.jpk-force", {"spring constant": 12}),
    ("fmt-jpk-fd_single-modified_2023.jpk-force", {"spring constant": 10, "sensitivity": 0.05}),
    ("fmt-jpk-fd_spot3-0192.jpk-force", {}),
    ("fmt-jpk-fd_spot3-0192.jpk-force", {"spring constant": 0.1}),
    ("fmt-jpk-sr_cell1-0008.jpk-force", {}),
    ("fmt-ntmdt-txt-fd_2015_01_17_gel4-0,1_mQ_adh_6B_Curve_DFL_Height_51.txt",
     {"spring constant": 0.055, "sensitivity": 61}),
    ("fmt-tab-fd_version_0.13.3.tab", {}),
]

N_SAMPLES = 8


def num(v):
    v = float(v)
    return v if np.isfinite(v) else None


def column_stats(a):
    a = np.asarray(a, dtype=float)
    n = a.size
    idx = sorted(set(int(round(i * (n - 1) / (N_SAMPLES - 1))) for i in range(N_SAMPLES))) if n else []
    return {
        "sum": num(np.sum(a)),
        "min": num(np.min(a)) if n else None,
        "max": num(np.max(a)) if n else None,
        "samples": [[i, num(a[i])] for i in idx],
    }


def load(path, override):
    if path.suffix == ".zip" and "chiaro" in path.name:
        # afmformats reads the text exports, not the zip: read each one unpacked.
        out = []
        with tempfile.TemporaryDirectory() as tmp:
            with zipfile.ZipFile(path) as arc:
                names = sorted(n for n in arc.namelist() if not n.endswith("/"))
                arc.extractall(tmp)
            for n in names:
                out += afmformats.load_data(pathlib.Path(tmp) / n, meta_override=override)
        return out
    return afmformats.load_data(path, meta_override=override)


def curve_record(data):
    md = data.metadata
    meta = {}
    for key, name in [("spring constant", "spring_constant"), ("sensitivity", "sensitivity")]:
        if key in md:
            meta[name] = num(md[key])
    if "position x" in md and "position y" in md:
        meta["position"] = [num(md["position x"]), num(md["position y"])]
    if "grid index x" in md and "grid index y" in md:
        meta["grid_index"] = [int(md["grid index x"]), int(md["grid index y"])]
    if "grid shape x" in md and "grid shape y" in md:
        meta["grid_shape"] = [int(md["grid shape x"]), int(md["grid shape y"])]
    if "grid size x" in md and "grid size y" in md:
        meta["grid_size"] = [num(md["grid size x"]), num(md["grid size y"])]
    seg = np.asarray(data["segment"])
    segments = []
    for s in sorted(set(int(v) for v in seg)):
        mask = seg == s
        cols = {}
        for col, name in COLUMNS.items():
            if col in data.columns_innate:
                cols[name] = column_stats(np.asarray(data[col])[mask])
        segments.append({"segment": s, "len": int(np.sum(mask)), "columns": cols})
    return {"meta": meta, "segments": segments}


def main():
    warnings.simplefilter("ignore")
    cases = []
    for name, override in CASES:
        curves = load(FIX / name, override)
        options = {}
        if "spring constant" in override:
            options["spring_constant"] = float(override["spring constant"])
        if "sensitivity" in override:
            options["sensitivity"] = float(override["sensitivity"])
        cases.append({
            "file": name,
            "options": options,
            "curves": [curve_record(c) for c in curves],
        })
        print(f"{name} {options}: {len(curves)} curve(s)")
    out = {
        "generator": f"benches/afmformats_reference.py with afmformats {afmformats.__version__}",
        "samples_per_column": N_SAMPLES,
        "cases": cases,
    }
    (FIX / "reference.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
