"""Sweeps cell counts and thicknesses on a saddle and prints the measures of each result."""

import sys

import numpy as np

import honeycomb


def saddle(n=25):
    x, y = np.meshgrid(np.linspace(-1, 1, n), np.linspace(-1, 1, n))
    vertices = np.stack([x.ravel(), y.ravel(), 0.1 * (x**2 - y**2).ravel()], axis=1)
    faces = [[i * n + j, i * n + j + 1, i * n + j + n + 1] for i in range(n - 1) for j in range(n - 1)]
    faces += [[i * n + j, i * n + j + n + 1, i * n + j + n] for i in range(n - 1) for j in range(n - 1)]
    return vertices, faces


surface = sys.argv[1] if len(sys.argv) > 1 else saddle()
print(f"{'cells':>6} {'thickness':>9} {'honeycomb':>9} {'omega_max':>10} {'delta_max':>10} {'axis-normal':>11}")
for cells in (100, 300, 1000):
    for thickness in (0.02, 0.05, 0.1):
        r = honeycomb.pipeline(surface, cells=cells, thickness=thickness)
        m = r.measures
        print(
            f"{cells:>6} {thickness:>9} {str(r.is_honeycomb):>9} {m['omega_max_deg']:>10.2e} "
            f"{m['delta_max']:>10.2e} {m['axis_normal_deg']['mean']:>11.2f}"
        )
