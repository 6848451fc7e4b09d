"""nanite's Hertz fit of the same curves the workbench fits, back to back.

Run with a Python that has nanite 4.2.3 (and afmformats 0.18.7):

    python benches/nanite_compare.py synthetic CURVE.csv K_N_PER_M R_M [NU]
        a curve written by `FORCE_CURVE_BENCH_WRITE=CURVE.csv cargo bench --bench force_curves`
        (columns segment,height_m,force_n; segment 0 approach, 1 retract)
    python benches/nanite_compare.py file INSTRUMENT_FILE R_M [NU]
        every curve of an instrument file as afmformats reads it

For each curve: nanite's preprocessing (compute_tip_position, correct_force_offset,
correct_tip_offset, correct_split_approach_retract), then the paraboloidal Hertz model
(`hertz_para`) on the approach segment, contact point and baseline free, the whole segment,
no contact-point weighting (weight_cp=0). Prints one JSON line per curve: Young's modulus E,
the plane-strain modulus E/(1-nu^2), the contact point, and the median time of the fit alone
(fit_model on a freshly preprocessed curve) over repeated runs.
"""
import json
import sys
import time

import numpy as np
import afmformats
import nanite

PREPROC = ["compute_tip_position", "correct_force_offset", "correct_tip_offset",
           "correct_split_approach_retract"]


def indentation(fd):
    # Asylum .ibw data come as float32, which nanite's fit hashing refuses: pass float64.
    raw = fd._raw_data
    if isinstance(raw, dict):
        raw = {k: (np.asarray(v, dtype=np.float64) if np.asarray(v).dtype == np.float32 else v)
               for k, v in raw.items()}
    return nanite.Indentation(raw, fd.metadata)


def fit(fd, radius, nu, repeats):
    times = []
    idnt = indentation(fd)
    idnt.apply_preprocessing(PREPROC)
    params = idnt.get_initial_fit_parameters(model_ancillaries=False)
    params["R"].set(value=radius)
    params["nu"].set(value=nu)
    idnt.fit_model(model_key="hertz_para", segment=0, weight_cp=0,
                   params_initial=params, x_axis="tip position", y_axis="force")
    t0 = time.perf_counter()
    for _ in range(repeats):
        idnt2 = indentation(fd)
        idnt2.apply_preprocessing(PREPROC)
        t1 = time.perf_counter()
        idnt2.fit_model(model_key="hertz_para", segment=0, weight_cp=0,
                        params_initial=params, x_axis="tip position", y_axis="force")
        times.append(time.perf_counter() - t1)
    times = [0.0] * repeats + times
    fp = idnt.fit_properties
    e = fp["params_fitted"]["E"].value
    return {
        "E_pa": e,
        "plane_strain_modulus_pa": e / (1 - nu ** 2),
        "contact_point_m": fp["params_fitted"]["contact_point"].value,
        "baseline_n": fp["params_fitted"]["baseline"].value,
        "fit_median_s": float(np.median(times[repeats:])),
        "points_approach": int(np.sum(idnt.data["segment"] == 0)),
        "success": bool(fp.get("success", True)),
    }


def main():
    mode = sys.argv[1]
    if mode == "synthetic":
        path, k, radius = sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
        nu = float(sys.argv[5]) if len(sys.argv) > 5 else 0.5
        d = np.loadtxt(path, delimiter=",", skiprows=1)
        n = len(d)
        data = {"force": d[:, 2], "height (measured)": d[:, 1],
                "segment": d[:, 0].astype(np.uint8),
                "time": np.arange(n) * 1e-3}
        meta = {"spring constant": k, "imaging mode": "force-distance",
                "sensitivity": 50e-9, "duration": n * 1e-3, "path": path,
                "enum": 0, "point count": n}
        fd = afmformats.mod_force_distance.AFMForceDistance(data, meta)
        print(json.dumps({"file": path, "curve": 0, **fit(fd, radius, nu, 20)}))
    else:
        path, radius = sys.argv[2], float(sys.argv[3])
        nu = float(sys.argv[4]) if len(sys.argv) > 4 else 0.5
        for i, fd in enumerate(afmformats.load_data(path)):
            if fd.modality != "force-distance":
                continue
            try:
                r = fit(fd, radius, nu, 5)
            except Exception as e:  # a curve nanite cannot fit
                r = {"error": str(e)}
            print(json.dumps({"file": path, "curve": i, **r}))


if __name__ == "__main__":
    main()
