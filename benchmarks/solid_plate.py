"""The reference plate as a mesh of quadratic hexahedra, for Exudyn's FFRF peer (case R).

    python benchmarks/solid_plate.py [NX ...]     # the mesh check for NX elements along the length

Exudyn builds the mass and stiffness matrices of a solid only through NGsolve (not a
dependency here); ``exudyn.FEM.FEMinterface`` accepts them by hand: ``nodes['Position']``
(n x 3 array, m), ``elements`` (a list of dicts, here ``{'Name': ..., 'Hex20': (ne x 20)}``
in Abaqus C3D20 order) and ``massMatrix`` / ``stiffnessMatrix`` as scipy CSR matrices over
the 3 n nodal displacements (node-major: x, y, z of node 0, then node 1, ...). This module
writes them for a box of 20-node serendipity hexahedra (Hex20, linear isotropic elasticity,
consistent mass, 3 x 3 x 3 Gauss points: exact for the box's constant Jacobian).

Geometry: x along the length [0, L], y along the thickness [-h/2, h/2] (so gravity -y bends
the weak axis, as in case A), z along the width [-b/2, b/2]; one element through the
thickness (Hex20 holds a linear bending strain through it exactly), two across the width
(so the tip-face centre (L, 0, 0) is a mesh node), NX along the length, graded towards the
clamp (element ends at L (k / NX)^2).

Measured (f1, f2 against Euler-Bernoulli 0.97803 and 6.12920 Hz): uniform NX = 16, 32, 64:
+1.67/+2.16, +0.99/+1.09, +0.64/+0.65 %; graded NX = 16, 32, 64: +0.55/+1.22, +0.38/+0.53,
+0.34/+0.37 %. The solid tends to about +0.33 % above the beam, an effect of Poisson's ratio
(with nu = 0 the uniform mesh gives +0.06 % at NX = 16, +0.01 % at 32): we attribute it to
the clamped face, which holds the plate's anticlastic (Poisson) deformation that the beam
theory leaves free, and have not separated it further. A 27-node (Lagrange) hexahedron
(uniform NX = 32: +0.69 %) converges no faster.

:func:`check` is the verification others can rerun: total mass against rho L b h and the
first two clamped frequencies (both weak-axis bending) against Euler-Bernoulli.
"""

from __future__ import annotations

import math
import sys

import numpy as np

L, B, H, E, NU, RHO = 1.45, 0.05, 0.0025, 70e9, 0.33, 2700.0

#: natural coordinates (xi, eta, zeta) of the 20 nodes, Abaqus C3D20 order: corners 0-7
#: (bottom zeta = -1 counter-clockwise, then top), mid-edge nodes 8-11 (bottom), 12-15 (top),
#: 16-19 (the edges along zeta)
HEX20_NODES = np.array([
    [-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1], [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1],
    [0, -1, -1], [1, 0, -1], [0, 1, -1], [-1, 0, -1], [0, -1, 1], [1, 0, 1], [0, 1, 1], [-1, 0, 1],
    [-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=float)

#: element ends along the length at L (k / nx)^GRADING: refined towards the clamp, where a
#: uniform mesh converges slowly (module docstring)
GRADING = 2.0

#: Euler-Bernoulli beta_n L of a clamped-free beam, n = 1, 2, 3
BETA_L = (1.8751040687, 4.6940911330, 7.8547574382)


def hex20_shapes(xi: float, eta: float, zeta: float) -> tuple[np.ndarray, np.ndarray]:
    """Serendipity shape functions N (20,) and their natural derivatives dN (20, 3) at a point."""
    N = np.empty(20)
    dN = np.empty((20, 3))
    for a, (xa, ya, za) in enumerate(HEX20_NODES):
        fx, fy, fz = 1 + xi * xa, 1 + eta * ya, 1 + zeta * za
        if xa != 0 and ya != 0 and za != 0:  # corner
            s = xi * xa + eta * ya + zeta * za - 2
            N[a] = fx * fy * fz * s / 8
            dN[a] = [xa * fy * fz * (s + fx) / 8, ya * fx * fz * (s + fy) / 8, za * fx * fy * (s + fz) / 8]
        elif xa == 0:
            N[a] = (1 - xi * xi) * fy * fz / 4
            dN[a] = [-2 * xi * fy * fz / 4, ya * (1 - xi * xi) * fz / 4, za * (1 - xi * xi) * fy / 4]
        elif ya == 0:
            N[a] = fx * (1 - eta * eta) * fz / 4
            dN[a] = [xa * (1 - eta * eta) * fz / 4, -2 * eta * fx * fz / 4, za * fx * (1 - eta * eta) / 4]
        else:
            N[a] = fx * fy * (1 - zeta * zeta) / 4
            dN[a] = [xa * fy * (1 - zeta * zeta) / 4, ya * fx * (1 - zeta * zeta) / 4, -2 * zeta * fx * fy / 4]
    return N, dN


def hex20_box_matrices(dx: float, dy: float, dz: float, youngs_modulus: float, poisson_ratio: float,
                       density: float) -> tuple[np.ndarray, np.ndarray]:
    """Stiffness (N/m) and consistent mass (kg) matrices, 60 x 60, of one Hex20 box of edges
    dx, dy, dz (m) along x, y, z; coordinates node-major (ux, uy, uz of node 0, ...)."""
    lam = youngs_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio))
    mu = youngs_modulus / (2 * (1 + poisson_ratio))
    elasticity = np.zeros((6, 6))  # Voigt: xx, yy, zz, yz, xz, xy (engineering shear strains)
    elasticity[:3, :3] = lam
    elasticity[np.arange(3), np.arange(3)] += 2 * mu
    elasticity[np.arange(3, 6), np.arange(3, 6)] = mu
    half = np.array([dx, dy, dz]) / 2  # d(x, y, z)/d(xi, eta, zeta)
    det_j = float(np.prod(half))
    points, weights = np.polynomial.legendre.leggauss(3)
    stiffness = np.zeros((60, 60))
    mass = np.zeros((60, 60))
    for i, wi in zip(points, weights):
        for j, wj in zip(points, weights):
            for k, wk in zip(points, weights):
                N, dN = hex20_shapes(i, j, k)
                grad = dN / half  # dN/dx (20, 3)
                strain = np.zeros((6, 60))
                strain[0, 0::3], strain[1, 1::3], strain[2, 2::3] = grad[:, 0], grad[:, 1], grad[:, 2]
                strain[3, 1::3], strain[3, 2::3] = grad[:, 2], grad[:, 1]
                strain[4, 0::3], strain[4, 2::3] = grad[:, 2], grad[:, 0]
                strain[5, 0::3], strain[5, 1::3] = grad[:, 1], grad[:, 0]
                w = wi * wj * wk * det_j
                stiffness += w * strain.T @ elasticity @ strain
                shape = np.kron(N, np.eye(3))  # (3, 60)
                mass += w * density * shape.T @ shape
    return stiffness, mass


def box_mesh(length: float, thickness: float, width: float, nx: int, ny: int = 1, nz: int = 2,
             grading: float = 1.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The box [0, length] x [-thickness/2, thickness/2] x [-width/2, width/2] in Hex20:
    node positions (n x 3, m), connectivity (nx ny nz x 20, elements ordered x fastest) and
    the element lengths along x (nx, m). Element ends along x at length (k / nx)^grading:
    grading 1 is uniform, 2 refines towards the clamp at x = 0."""
    ends = length * (np.arange(nx + 1) / nx) ** grading
    x_lattice = np.empty(2 * nx + 1)  # element ends and their mid-points (the mid-edge nodes)
    x_lattice[0::2], x_lattice[1::2] = ends, (ends[:-1] + ends[1:]) / 2
    grid = {}  # (i, j, k) on the half-element lattice -> node number; serendipity: at most one odd index
    positions = []
    for i in range(2 * nx + 1):
        for j in range(2 * ny + 1):
            for k in range(2 * nz + 1):
                if i % 2 + j % 2 + k % 2 <= 1:
                    grid[i, j, k] = len(positions)
                    positions.append([x_lattice[i], thickness * (j / (2 * ny) - 0.5), width * (k / (2 * nz) - 0.5)])
    offsets = (HEX20_NODES + 1).astype(int)
    elements = [[grid[2 * ex + a, 2 * ey + b, 2 * ez + c] for a, b, c in offsets]
                for ez in range(nz) for ey in range(ny) for ex in range(nx)]
    return np.array(positions), np.array(elements), np.diff(ends)


def assemble(positions: np.ndarray, elements: np.ndarray, element_stiffness: np.ndarray,
             element_mass: np.ndarray):
    """Global stiffness and mass (scipy CSR, 3 n x 3 n) from the elements' 60 x 60 matrices
    (``element_stiffness``, ``element_mass``: one per element, ne x 60 x 60)."""
    from scipy.sparse import coo_matrix

    dofs = (3 * elements[:, :, None] + np.arange(3)).reshape(len(elements), 60)
    rows = np.repeat(dofs, 60, axis=1).ravel()
    cols = np.tile(dofs, (1, 60)).ravel()
    size = 3 * len(positions)
    stiffness = coo_matrix((element_stiffness.ravel(), (rows, cols)), shape=(size, size))
    mass = coo_matrix((element_mass.ravel(), (rows, cols)), shape=(size, size))
    return stiffness.tocsr(), mass.tocsr()


def plate_fem(nx: int, modes: int = 4, grading: float = GRADING):
    """An ``exudyn.FEM.FEMinterface`` holding the plate (nx x 1 x 2 Hex20, :func:`box_mesh`),
    and its ``modes`` lowest modes clamped at x = 0 (Hurty-Craig-Bampton with one RBE2
    interface, the clamp face, whose rigid motion is excluded: the fixed-interface eigenmodes
    alone). Returns (fem, clamp node numbers, tip node number at (L, 0, 0))."""
    from exudyn.FEM import FEMinterface, HCBstaticModeSelection

    positions, elements, lengths = box_mesh(L, H, B, nx, grading=grading)
    per_length = [hex20_box_matrices(dx, H, B / 2, E, NU, RHO) for dx in lengths]
    column = np.arange(len(elements)) % nx  # elements are ordered x fastest
    stiffness, mass = assemble(positions, elements, np.array([per_length[c][0] for c in column]),
                               np.array([per_length[c][1] for c in column]))
    fem = FEMinterface()
    fem.nodes = {"Position": positions}
    fem.elements = [{"Name": "plate", "Hex20": elements}]
    fem.massMatrix, fem.stiffnessMatrix = mass, stiffness
    fem.VolumeToSurfaceElements()
    clamp = np.flatnonzero(positions[:, 0] == 0.0)
    tip = int(fem.GetNodeAtPoint([L, 0.0, 0.0]))
    fem.ComputeHurtyCraigBamptonModes(boundaryNodesList=[clamp], nEigenModes=modes, useSparseSolver=True,
                                      computationMode=HCBstaticModeSelection.RBE2)
    return fem, clamp, tip


def euler_bernoulli_hz(n: int, second_moment: float) -> float:
    """Clamped-free Euler-Bernoulli frequency n (1-based) of the plate bending about an axis
    with ``second_moment`` (m^4), Hz."""
    return BETA_L[n - 1] ** 2 / (2 * math.pi * L**2) * math.sqrt(E * second_moment / (RHO * B * H))


def check(fem) -> dict:
    """The mesh's verification: total mass (kg) from the mass matrix (a rigid translation's
    kinetic energy) against rho L b h, and the first two clamped frequencies (Hz) against
    Euler-Bernoulli weak-axis bending (I = b h^3 / 12); their relative errors."""
    translation = np.zeros(fem.massMatrix.shape[0])
    translation[1::3] = 1.0
    mass = float(translation @ (fem.massMatrix @ translation))
    frequencies = [float(f) for f in fem.GetEigenFrequenciesHz()]
    weak = B * H**3 / 12
    analytic = [euler_bernoulli_hz(1, weak), euler_bernoulli_hz(2, weak)]
    return {"mesh_nodes": len(fem.nodes["Position"]), "mass_kg": mass, "mass_exact_kg": RHO * L * B * H,
            "mass_error": mass / (RHO * L * B * H) - 1,
            "f_hz": frequencies, "f_weak_eb_hz": analytic,
            "f1_error": frequencies[0] / analytic[0] - 1, "f2_error": frequencies[1] / analytic[1] - 1,
            "f_strong1_eb_hz": euler_bernoulli_hz(1, H * B**3 / 12), "f_weak3_eb_hz": euler_bernoulli_hz(3, weak)}


if __name__ == "__main__":
    for nx in [int(a) for a in sys.argv[1:]] or [8, 16, 32]:
        c = check(plate_fem(nx)[0])
        print(f"{nx:3d} x 1 x 2 Hex20, graded ({c['mesh_nodes']} nodes): mass {c['mass_kg']:.6f} kg "
              f"(rho L b h {c['mass_exact_kg']:.6f}, {c['mass_error']:+.1e}); f = "
              + ", ".join(f"{f:.4f}" for f in c["f_hz"])
              + f" Hz; weak-axis EB {c['f_weak_eb_hz'][0]:.4f}, {c['f_weak_eb_hz'][1]:.4f} Hz "
              f"({100 * c['f1_error']:+.2f} %, {100 * c['f2_error']:+.2f} %); "
              f"EB weak 3: {c['f_weak3_eb_hz']:.3f}, strong 1: {c['f_strong1_eb_hz']:.3f} Hz")
