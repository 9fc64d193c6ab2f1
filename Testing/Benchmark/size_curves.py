"""cbc3d's side of the size curves: meshes at tet budgets (--max-tets), and how they compare
with CGAL Mesh_3 at the same number of tets.

Each budget runs with the paper's fidelity 0.95 and edge pattern. Where the mesh stops short of
the budget because every tissue reached 0.95 first, the budget runs again at fidelity 0.99, so
that the curve reaches the larger sizes. CGAL's figures at cbc3d's tets are interpolated along
its size-factor curve, linearly in log(tets); a budget outside CGAL's range is not compared."""
import math

FIDELITIES = ("0.95", "0.99")
FIGURES = ("hausdorff_mm", "hausdorff_95_mm", "mean_distance_mm")
BUDGET_SPENT = "the tet budget is spent"


def budget_curve(run, budgets, progress):
    """Points of run(settings) -> report at each budget: the report's figures, the budget and
    the fidelity used. `run` returns the --report JSON (or {"error": ...})."""
    points = []
    for budget in budgets:
        for fidelity in FIDELITIES:
            progress("  cbc3d --max-tets %d --fidelity %s" % (budget, fidelity))
            report = run(["--max-tets", str(budget), "--fidelity", fidelity, "--pattern", "edge"])
            reason = report.get("refinement", {}).get("stop_reason", "")
            if "error" in report or reason == BUDGET_SPENT or fidelity == FIDELITIES[-1]:
                break
        points.append(dict(report, budget=budget, fidelity=float(fidelity)))
    return points


def interpolate(curve, tets, key):
    """The figure `key` of a curve (points with "tetrahedra") at `tets`, linear in log(tets);
    None outside the curve."""
    ordered = sorted((p["tetrahedra"], p[key]) for p in curve if "tetrahedra" in p and p.get(key) is not None)
    for (t0, v0), (t1, v1) in zip(ordered, ordered[1:]):
        if t0 <= tets <= t1 and t1 > t0:
            share = (math.log(tets) - math.log(t0)) / (math.log(t1) - math.log(t0))
            return v0 + share * (v1 - v0)
    return None


def equal_size_rows(name, ours, theirs):
    """Markdown rows: each cbc3d point against CGAL at its tets (HD, 95th percentile, mean, and
    cbc3d / CGAL for each; below 1 is cbc3d's lead)."""
    rows = []
    for p in ours:
        if "tetrahedra" not in p or any(p.get(key) is None for key in FIGURES):
            continue
        row = [name, "%d" % p["budget"], "%d" % p["tetrahedra"]]
        for key in FIGURES:
            cgal = interpolate(theirs, p["tetrahedra"], key)
            row += ["%.2f / %s" % (p[key], "%.2f" % cgal if cgal is not None else "-"),
                    "%.2f" % (p[key] / cgal) if cgal else "-"]
        rows.append(row)
    return rows


EQUAL_SIZE_HEADER = ["image", "budget", "tets", "HD cbc3d / CGAL mm", "ratio", "95% cbc3d / CGAL mm", "ratio",
                     "mean cbc3d / CGAL mm", "ratio"]
