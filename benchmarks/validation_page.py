# ruff: noqa: E501  (the markdown table of the inputs: one row a line)
"""docs/validation.md from the deviations of benchmarks/validation.py (make validate)."""

from __future__ import annotations

from pathlib import Path

INTRO = """\
# Validation: Chung & Ooi (2011) tests 1 to 8 and Kharaz et al. (2001)

<!-- Written by `make validate` (benchmarks/validation.py): do not edit by hand. -->

Chung & Ooi's benchmark (Y. C. Chung, J. Y. Ooi, "Benchmark tests for verifying discrete
element modelling codes at particle impact level", Granular Matter 13:643-656, 2011,
doi:10.1007/s10035-011-0277-0) is eight impacts of one or two spheres, each with its
inputs and the results a DEM code should give. Every one is run here with this tool's
normal law and each of its tangential models ({doc}`collision3d`), on the paper's inputs,
against the published curves and against the experiment of Kharaz, Gorham & Salman (2001,
Powder Technol. 120:281-291: 5 mm alumina spheres on a glass anvil at 3.9 m/s).

**Where the numbers come from.** The paper's curves are not published as numbers; the ones
used here are the digitisations in public DEM repositories, kept as data in
`benchmarks/data/validation/` (each file names its source: repository, path and commit):
the Kratos DEM application's `paper_data` (KratosMultiphysics/Kratos, tests 1, 2 and 4 to
8, and the experiment as Chung & Ooi plot it) and the Lethe example of the experiment
(chaos-polymtl/lethe, Kharaz et al.). The inputs of each test are those of the public DEM
scripts of the benchmark (Yade's `Test1.py` ... `Test4.py`, PySPH's tests 5 to 8, Kratos's
`benchmark*DEM.mdpa`): the table below.

| test | impact | materials (E, nu, rho) | R | velocities | mu, e_n |
|---|---|---|---|---|---|
| 1 | two identical spheres head on | glass (48 GPa, 0.20, 2800), limestone (20 GPa, 0.25, 2500) | 10 mm | 10 m/s each | -, 1 |
| 2 | sphere on a rigid plane | aluminium alloy (70 GPa, 0.30, 2699), magnesium alloy (40 GPa, 0.35, 1800) | 0.1 m | 0.2 m/s | -, 1 |
| 3 | sphere on a rigid plane, e asked | alumina (380 GPa, 0.23, 4000), cast iron (100 GPa, 0.25, 7000) | 2.5 mm | 3.9 m/s | -, 0.1 to 1 |
| 4 | oblique, constant speed | alumina, aluminium alloy (70 GPa, 0.33, 2700) | 2.5 mm | 3.9 m/s at 1 to 89 deg | 0.092, 0.98 |
| 5 | oblique, constant normal velocity | steel (208 GPa, 0.30, 7850), polyethylene (1 GPa, 0.40, 1400) | 10 um | u_n = 5 m/s, u_t = psi mu u_n | 0.3, 1 |
| 6 | backspin on a rigid plane | aluminium alloy, nylon (2.5 GPa, 0.40, 1000) | 0.1 m | u_n = 0.2 m/s, R w = u_t | 0.4, 0.5 |
| 7 | two identical spheres, opposite spins | aluminium alloy, copper (120 GPa, 0.35, 8900) | 0.1 m | 0.2 m/s each | 0.4, 0.5 |
| 8 | backspin on a larger sphere (R2 = 0.5 m, 1000 x E and rho) | aluminium alloy, nylon | 0.1 m | u_n = 0.2 m/s | 0.4, 0.5 |

e_n < 1 is Hertz with the Tsuji damping that gives it (`impact collide3d --e E` with a
tangential spring; LAMMPS's `damping coeff_restitution`); 1 is Hertz. `make validate`
regenerates the figures, this page and `benchmarks/data/validation/deviations.csv`;
`tests/test_validation.py` (slow tier) fails where a deviation grows beyond the table's.

**What the tool does not cover, and why.** Every one of the eight tests runs, but: test
8's case B, whose inputs differ from case A's in a way the public scripts do not agree on
(PySPH's and Kratos's), is drawn and not tabulated; test 5's FEM curve (Chung & Ooi's
finite-element reference, partial slip resolved) and the experiment are drawn beside the
models, not fitted. The tool's models are of spheres: the glass anvil of the experiment is
taken rigid, as in the paper, and its e_n (0.98, the paper's) stands for the measured one.

**What is reproduced.** Tests 1 to 3 (no friction) and 7 (no slip) to rounding or to the
digitisation: the largest force of test 1 (limestone) is 7108.24 N against Chung & Ooi's
7108, of test 2 (magnesium alloy) 7233.3 against 7233, and the e asked for in test 3 is
the e of the impact to 1e-14. Test 4's curves are reproduced by `mindlin-displacement`
(the tangential force is the current stiffness k_t = 8 G* a times the tangential
displacement accumulated since the last slide, LAMMPS's `tangential mindlin`; bold in the
figures) within their digitisation: spin RMS 3.4 rad/s for alumina and 2.8 for the
aluminium alloy (of 620), v_t'/v_t 0.004 and 0.002; the other Mindlin springs are 2 to 4
times further away, `mindlin` (LAMMPS's `mindlin_rescale/force`) by 9 rad/s and 0.025, most
at 5 to 10 deg. A displacement accumulated over the whole contact without its reset at a
slide (F_t = k_t times the integral of u_t from first contact) is not their form: it gives
374 rad/s at 10 deg where the curve has 213. In gross slip (large angles, small psi) every
spring meets every published curve of tests 4 to 8.

**What is not.** Below gross slip the published curves of tests 5, 6 and 8 are reproduced
by none of the tool's models: where the contact sticks, Chung & Ooi's curves reverse the
contact point's slip (test 5: u_t'/(mu u_n') about -0.75 psi; test 6: beta no larger than
0.12), while every Mindlin spring, as LAMMPS implements it and as this tool integrates it
(checked against LAMMPS and SciPy), lets the tangential oscillation end the slip forward or
reverse it by up to beta = 0.5; Mindlin-Deresiewicz comes nearest to the FEM curve of test
5 beyond psi = 2. The model behind those curves is not one of the tool's, and the public
sources do not say which it is: the deviations below are the measure of the difference,
not of an error of integration. Against the experiment, Mindlin-Deresiewicz (Thornton &
Yin's partial slip, the reference theory) is the nearest in spin (RMS 25 rad/s) and in the
rebound angle of the centre; the rigid model is nearest in v_t'/v_t, which no model
follows below 5 deg.

## The deviations

The tool's value minus the published one at each published point, RMS and largest
(`|max|`), in the quantity's unit: one row per published curve, one column per model.
"""

FIGURES = """
## The figures

```{image} figures/validation/test1.png
:alt: Chung & Ooi test 1
```

```{image} figures/validation/test2.png
:alt: Chung & Ooi test 2
```

```{image} figures/validation/test3.png
:alt: Chung & Ooi test 3
```

```{image} figures/validation/test4.png
:alt: Chung & Ooi test 4
```

```{image} figures/validation/kharaz.png
:alt: Kharaz, Gorham & Salman 2001
```

```{image} figures/validation/test5.png
:alt: Chung & Ooi test 5
```

```{image} figures/validation/test6.png
:alt: Chung & Ooi test 6
```

```{image} figures/validation/test7.png
:alt: Chung & Ooi test 7
```

```{image} figures/validation/test8.png
:alt: Chung & Ooi test 8
```
"""


def _cell(rms: float, largest: float) -> str:
    return f"{rms:.3g} / {largest:.3g}"


def write_page(rows, path: Path) -> None:
    """The page: the introduction, the table of deviations, the figures."""
    from validation import VARIANTS  # benchmarks/validation.py

    keys: list[tuple[str, str, str, str]] = []
    cells: dict[tuple[str, str, str, str], dict[str, str]] = {}
    for r in rows:
        key = (r.test, r.quantity, r.series, r.unit)
        if key not in cells:
            keys.append(key)
            cells[key] = {}
        cells[key][r.model] = _cell(r.rms, r.largest)
    lines = [INTRO]
    header = "| test | quantity | curve | unit | " + " | ".join(VARIANTS) + " |"
    lines += [header, "|" + "---|" * 4 + "---:|" * len(VARIANTS)]
    for key in keys:
        test, quantity, series, unit = key
        row = cells[key]
        if "normal law" in row:  # tests 1 to 3: no tangential model
            values = [row["normal law"]] + [""] * (len(VARIANTS) - 1)
        else:
            values = [row.get(model, "") for model in VARIANTS]
        lines.append(f"| {test} | {quantity} | {series} | {unit} | " + " | ".join(values) + " |")
    lines.append("")
    lines.append("Tests 1 to 3 have no tangential model: their one number is the normal law's "
                 "(FILM, n = 100; Tsuji damping for test 3).")  # fmt: skip
    lines.append(FIGURES)
    path.write_text("\n".join(lines))
