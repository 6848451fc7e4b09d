"""Hertz fits of the real force-distance files: the workbench against nanite, back to back.

    python benches/nanite_hertz_table.py ADHESION_BINARY [FILES...]

For each file (default: the force-distance fixtures under tests/fixtures/afm) and each of its
first curves, runs `ADHESION_BINARY --headless --fit FILE --curve I --model hertz --tip-radius R
--poisson 0.5` and nanite's Hertz fit (benches/nanite_compare.py: approach segment, contact
point and baseline free, no contact-point weighting) with the same R and nu, and prints a
Markdown table of Young's modulus E from both and their relative difference.

    python benches/nanite_hertz_table.py --reference
writes nanite's E of the same curves to tests/fixtures/afm/nanite_hertz.json (with R, nu and the
versions), the reference of the test `hertz_fits_agree_with_nanite` (tests/it/force_curves.rs).
"""
import json
import pathlib
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).parent))
import afmformats  # noqa: E402
import nanite  # noqa: E402
import nanite_compare  # noqa: E402

R, NU = 5e-6, 0.5


def ours(binary, path, curve):
    with tempfile.TemporaryDirectory() as out:
        r = subprocess.run([binary, "--headless", "--fit", str(path), "--curve", str(curve),
                            "--model", "hertz", "--tip-radius", str(R), "--poisson", str(NU),
                            "--out", out], capture_output=True, text=True)
        if r.returncode != 0:
            return None, r.stderr.strip().splitlines()[-1] if r.stderr else "failed"
        j = json.load(open(pathlib.Path(out) / "fit.json"))
        j = j.get("fit", j)
        return j["youngs_modulus_pa"]["value"], "; ".join(j["warnings"])


def reference(root):
    out = {"nanite": nanite.__version__ if hasattr(nanite, "__version__") else "?",
           "afmformats": afmformats.__version__, "tip_radius_m": R, "poisson": NU,
           "segment": "approach", "curves": []}
    for path in sorted(p for p in root.glob("fmt-*")
                       if "-fd" in p.name and "workshop" not in p.name and "ntmdt" not in p.name):
        try:
            data = afmformats.load_data(path)
        except BaseException:
            continue
        for i, fd in enumerate(data[:2]):
            r = nanite_compare.fit(fd, R, NU, 1)
            out["curves"].append({"file": path.name, "curve": i, "youngs_modulus_pa": r["E_pa"]})
    dest = root / "nanite_hertz.json"
    dest.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {dest} ({len(out['curves'])} curves)")


def main():
    root = pathlib.Path(__file__).resolve().parent.parent / "tests/fixtures/afm"
    if sys.argv[1] == "--reference":
        return reference(root)
    binary = sys.argv[1]
    root = pathlib.Path(__file__).resolve().parent.parent / "tests/fixtures/afm"
    files = [pathlib.Path(f) for f in sys.argv[2:]] or sorted(
        p for p in root.glob("fmt-*")
        if "-fd" in p.name and "workshop" not in p.name and "ntmdt" not in p.name)
    print("| file | curve | E nanite [Pa] | E workbench [Pa] | difference | workbench warnings |")
    print("|---|---|---|---|---|---|")
    for path in files:
        try:
            data = afmformats.load_data(path)
        except BaseException as e:  # files afmformats needs metadata for
            print(f"| {path.name} | - | afmformats: {e} | | | |")
            continue
        for i, fd in enumerate(data[:2]):
            try:
                n = nanite_compare.fit(fd, R, NU, 1)["E_pa"]
            except Exception as e:
                n = None
            e, warn = ours(binary, path, i)
            diff = f"{(e - n) / n:+.2%}" if (e and n) else "-"
            print(f"| {path.name} | {i} | {n if n is None else f'{n:.4g}'} | "
                  f"{e if e is None else f'{e:.4g}'} | {diff} | {warn} |")


if __name__ == "__main__":
    main()
