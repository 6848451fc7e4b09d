"""The comparison of benches/fe.rs `fe/assemble + factorise + solve`: the same-sized
axisymmetric linear elasticity problem in scikit-fem (https://github.com/kinnala/scikit-fem):
a 200 000-triangle mesh of a cylinder r <= 1, 0 <= z <= 1 (linear triangles), assembly of
the axisymmetric stiffness (hoop strain u_r/r, weight 2 pi r), the top held, a unit pressure
on the bottom face, and one sparse direct solve (scipy's spsolve, as skfem.solve does).

Run: pip install scikit-fem scipy numpy; OMP_NUM_THREADS=1 python3 benches/fe_skfem.py
Prints the median of 5 runs of (assembly + solve) and of assembly alone.
"""
import time

import numpy as np
from skfem import Basis, BilinearForm, ElementTriP1, ElementVector, MeshTri, condense, solve, LinearForm, FacetBasis
from skfem.helpers import dot

E, NU = 1.0, 0.25
LAM = E * NU / ((1 + NU) * (1 - 2 * NU))
MU = E / (2 * (1 + NU))


@BilinearForm
def axisymmetric(u, v, w):
    r = w.x[0]
    # strains (rr, zz, tt, rz) of u = (u_r, u_z) and of v
    def strains(f):
        g = f.grad
        return g[0, 0], g[1, 1], f.value[0] / r, g[0, 1] + g[1, 0]

    urr, uzz, utt, urz = strains(u)
    vrr, vzz, vtt, vrz = strains(v)
    tr_u = urr + uzz + utt
    tr_v = vrr + vzz + vtt
    return 2 * np.pi * r * (LAM * tr_u * tr_v + 2 * MU * (urr * vrr + uzz * vzz + utt * vtt) + MU * urz * vrz)


@LinearForm
def pressure(v, w):
    return 2 * np.pi * w.x[0] * v.value[1]


def run(n):
    t0 = time.perf_counter()
    mesh = MeshTri.init_tensor(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    basis = Basis(mesh, ElementVector(ElementTriP1()), intorder=3)
    K = axisymmetric.assemble(basis)
    bottom = FacetBasis(mesh, basis.elem, facets=mesh.facets_satisfying(lambda x: x[1] < 1e-12))
    f = pressure.assemble(bottom)
    t1 = time.perf_counter()
    top = basis.get_dofs(lambda x: x[1] > 1 - 1e-12).all()
    axis = basis.get_dofs(lambda x: x[0] < 1e-12).nodal["u^1"]
    fixed = np.unique(np.concatenate([top, axis]))
    u = solve(*condense(K, f, D=fixed))
    t2 = time.perf_counter()
    return mesh.t.shape[1], t1 - t0, t2 - t0


if __name__ == "__main__":
    n = 316  # 2 n^2 = 199 712 triangles
    runs = [run(n) for _ in range(5)]
    tri = runs[0][0]
    print(f"triangles {tri}: assembly median {np.median([r[1] for r in runs]):.3f} s, "
          f"assembly + solve median {np.median([r[2] for r in runs]):.3f} s")
