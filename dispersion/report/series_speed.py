"""Report section: speed of the series engine against Maxima, and its growth with the patch.

``measure`` is :func:`dispersion.studies.series_race.measure`; ``render`` writes
``series_speed.png`` from the stored JSON and returns the Markdown. The headline is the
whole-process comparison (both cold, as a user runs them); the compute-only comparison
(ours in-process against the time Maxima reports itself) is given beside it.
"""
from __future__ import annotations

from pathlib import Path

from dispersion.io import save_figure
from dispersion.report.compare import Peer, machine, timing
from dispersion.studies.series_race import MAXIMA_INSTALL, measure

__all__ = ["measure", "render", "render_tables", "summary", "missing_peers", "TOLERANCES"]

#: Comparison rules (:mod:`dispersion.report.compare`): a speed study, so every measurement
#: is a timing (listed as a ratio, not judged); its settings must be identical. Whether
#: Maxima is installed, and how its runs went, is the machine's business (said in the
#: verdict by :func:`missing_peers`); the series themselves are judged in the coefficients
#: section and by the test suite.
TOLERANCES = (
    timing("race[].*_s", "wall time"),
    timing("race[].*_mib", "peak memory of the process"),
    timing("scaling[].seconds", "wall time"),
    timing("fits[].*", "fitted to wall times"),
    machine("race[].agree", "Maxima's run compared with ours: needs Maxima on the machine"),
    machine("race[].maxima_*", "Maxima's run: present or not, its status and message"),
    machine("maxima", "version of Maxima on the machine, or none"),
    machine("notes[]", "notes on the machine: peers and tools found or not, the install"),
)


def missing_peers(data: dict) -> tuple[Peer, ...]:
    """Maxima not installed, or its failed runs, as the stored result shows them.

    >>> missing_peers({"maxima": None, "race": [{"order": 8, "maxima_status": None}]})[0].line()
    'Maxima not installed: race not run; apt-get install maxima maxima-share'
    """
    if data.get("maxima") is None:
        return (Peer("Maxima", "not installed", "race not run", MAXIMA_INSTALL),)
    failed = [p for p in data.get("race", ()) if p.get("maxima_status") == "failed"]
    if not failed:
        return ()
    orders = ", ".join(f"kappa^{p['order']}" for p in failed)
    return (Peer("Maxima", f"failed at {orders}", "those runs not timed (series_speed.md)",
                 f"its message: {failed[0].get('maxima_error') or 'none'}"),)


def _fmt(x, digits: int = 3) -> str:
    return "-" if x is None else f"{x:.{digits}g}"


def _ratio(theirs, ours) -> str:
    return "-" if not theirs or not ours else f"{theirs / ours:.2g}x"


def render(data: dict, out: Path) -> str:
    """Chart and Markdown from the stored result of :func:`measure` (no recomputation)."""
    from dispersion.plotting import new_figure
    from dispersion.plotting.speed import plot_race, plot_scaling

    out = Path(out)
    fig = new_figure(figsize=(11, 4.2))
    a1, a2 = fig.subplots(1, 2)
    plot_race(data["race"], a1)
    a1.set_title("exact Rayleigh-Lamb S0 + A0 series: ours vs Maxima", fontsize="small")
    plot_scaling(data["scaling"], data["fits"], a2)
    a2.set_title(f"discrete series against patch size\n{_scaling_patch(data['scaling'])}",
                 fontsize="small")
    save_figure(fig, out / "series_speed.png", dpi=130)
    return ("## Speed of the series engine\n\n![series speed](series_speed.png)\n\n"
            + render_tables(data))


def _scaling_patch(points) -> str:
    """The patches of the scaling study but p, n and the mass, from what its points stored:
    ``Bloch r = b/h = 2; singular: contact top, gamma_s = 1/2``."""
    if not points or not all(q.get("patch") for q in points):
        return "patch not recorded in this older result"
    from dispersion.symbolic.patch import Patch

    specs = [Patch.from_dict(q["patch"]) for q in points]
    geometry = " / ".join(dict.fromkeys(
        "Bloch r = b/h = " + str(sp.r) if sp.model == "bloch" else "x-exact" for sp in specs))
    singular = " / ".join(dict.fromkeys(f"{sp.mass_name}: contact {sp.contact}, gamma_s = "
                                        f"{sp.gamma_s}" for sp in specs if sp.singular))
    return geometry + (f"; {singular}" if singular else "")


def _counted(p: dict) -> bool:
    """A peer run counts only if it succeeded (older records: timed and agreeing)."""
    status = p.get("maxima_status")
    if status is None:
        return bool(p.get("maxima_process_s")) and p.get("agree") is True
    return status == "ok"


def _failures(race) -> str:
    failed = [p for p in race if p.get("maxima_status") == "failed"]
    if not failed:
        return ""
    return ("**Maxima failed** (no time, memory or ratio is given for a failed run): "
            + "; ".join(f"kappa^{p['order']}: {p.get('maxima_error') or 'failed'}"
                        for p in failed) + ".\n\n")


def _peer_cell(p: dict) -> str:
    if p.get("maxima_status") == "failed":
        return "FAILED"
    return "-" if p.get("agree") is None else ("yes" if p["agree"] else "NO")


def render_tables(data: dict) -> str:
    """The Markdown of the section without the chart (headline, race table, growth table)."""
    race, points, fits = data["race"], data["scaling"], data["fits"]
    raced = [p for p in race if _counted(p)]
    if raced:
        head = "; ".join(
            f"kappa^{p['order']}: {_ratio(p['maxima_process_s'], p['ours_process_s'])}"
            for p in raced)
        comp = "; ".join(
            f"kappa^{p['order']}: {_ratio(p['maxima_compute_s'], p['ours_compute_s'])}"
            for p in raced)
        headline = (
            "**Headline (whole process, both cold, as a user runs them)**: Maxima's time over "
            f"ours is {head} (above 1: we are faster). Compute only (ours in-process vs the "
            f"time Maxima reports itself): {comp}. Only runs whose every coefficient agrees "
            "with ours (compared exactly at two values of nu) are timed.\n\n")
    else:
        headline = "No Maxima run succeeded; only our times are shown.\n\n"
    headline = _failures(race) + headline
    rows = ["| kappa^K | ours process s | Maxima process s | Maxima/ours | ours lean entry s | "
            "ours compute s | Maxima compute s | Maxima/ours | peak MiB ours / Maxima | "
            "Maxima run agrees |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for p in race:
        ok = _counted(p)
        m_proc = p["maxima_process_s"] if ok else None
        m_comp = p["maxima_compute_s"] if ok else None
        m_peak = p["maxima_peak_mib"] if ok else None
        rows.append(
            f"| {p['order']} | {_fmt(p['ours_process_s'])} | {_fmt(m_proc)} | "
            f"{_ratio(m_proc, p['ours_process_s'])} | "
            f"{_fmt(p.get('ours_lean_process_s'))} | {_fmt(p['ours_compute_s'])} | "
            f"{_fmt(m_comp)} | {_ratio(m_comp, p['ours_compute_s'])} | "
            f"{_fmt(p['ours_peak_mib'], 4)} / {_fmt(m_peak, 4)} | {_peer_cell(p)} |")
    fit_rows = ["| mass | p | n | fitted exponent b (t ~ n^b) | rms log residual | "
                "monotone in n |", "|---|---|---|---|---|---|"]
    for f in fits:
        ns = sorted(q["n"] for q in points if q["mass"] == f["mass"] and q["p"] == f["p"])
        fit_rows.append(f"| {f['mass']} | {f['p']} | {ns[0]}..{ns[-1]} ({f['points']} points) | "
                        f"{f['exponent']:.2f} | {f['residual']:.2f} | "
                        f"{'yes' if f['monotone'] else 'no'} |")
    sizes = {(q["mass"], q["p"], q["n"]): q["seconds"] for q in points}
    ns = sorted({n for m, p, n in sizes if p == 2 and m == "singular"
                 and ("consistent", 2, n) in sizes})
    ratio = ""
    if ns:
        shown = [n for n in (8, ns[-1]) if n in ns] or ns[-1:]
        ratio = (" The singular mass (no mirror symmetry: one full determinant) takes "
                 + ", ".join(f"{sizes[('singular', 2, n)] / sizes[('consistent', 2, n)]:.2g}x "
                             f"(n = {n})" for n in dict.fromkeys(shown))
                 + " the time of the consistent mass (two mirror blocks) at p = 2.")
    notes = "".join(f"- {n}\n" for n in data.get("notes", ()))
    order = points[0]["order"] if points else "?"
    return (
        headline
        + "Ours: `python -m dispersion series --exact --branch both --order K --format json`; "
          "Maxima: `maxima --very-quiet -b` on `dispersion/data/rayleigh_lamb_series.mac` "
          "(CRE arithmetic truncated with `ratweight`/`ratwtlvl`, Horner evaluation, leading "
          "balance once, one linear equation per order). Peak memory is each child's own "
          "resident peak. The lean entry `python -m dispersion.cli.series` runs the same "
          "command without importing the other subcommands (and sympy); it shows the start-up "
          "cost that the `dispersion` entry point adds. Maxima's own timer "
          "(`elapsed_run_time()`) ticks in steps of 10 ms, so its compute times below 0.1 s "
          "are coarse.\n\n" + "\n".join(rows) + "\n\n"
        + f"Cost of the discrete S0 + A0 series to kappa^{order} (nu symbolic, "
          f"{_scaling_patch(data['scaling'])}; "
          "fraction-free elimination over truncated series, polynomial in n for every mass)."
        + ratio + " Growth fitted by least squares on log t against log n:\n\n"
        + "\n".join(fit_rows) + "\n\n"
        + (f"Notes:\n\n{notes}\n" if notes else "")
        + "Data: `series_speed.json`. Regenerate: `dispersion reproduce` (this section: "
          "`dispersion bench --out DIR`).\n")


def summary(data: dict) -> str:
    """The README block: every number from the stored result (``dispersion reproduce``)."""
    race, points, fits = data["race"], data["scaling"], data["fits"]
    lines = []
    raced = [p for p in race if _counted(p)]
    for p in raced:
        lines.append(
            f"- Rayleigh-Lamb S0 + A0 to kappa^{p['order']}, whole process (cold): ours "
            f"{_fmt(p['ours_process_s'])} s (lean entry `python -m dispersion.cli.series`: "
            f"{_fmt(p.get('ours_lean_process_s'))} s), Maxima {_fmt(p['maxima_process_s'])} s "
            f"(Maxima/ours {_ratio(p['maxima_process_s'], p['ours_process_s'])}); compute only "
            f"{_fmt(p['ours_compute_s'])} s vs {_fmt(p['maxima_compute_s'])} s "
            f"({_ratio(p['maxima_compute_s'], p['ours_compute_s'])}); coefficients "
            "identical.")
    for p in race:
        if p.get("maxima_status") == "failed":
            lines.append(f"- Maxima to kappa^{p['order']} FAILED, not timed: "
                         f"{p.get('maxima_error') or 'failed'}.")
    for p in race:
        if not _counted(p) and p.get("ours_process_s"):
            lines.append(f"- Ours alone to kappa^{p['order']}: {_fmt(p['ours_process_s'])} s "
                         f"whole process, peak {_fmt(p['ours_peak_mib'], 3)} MiB.")
    sizes = {(q["mass"], q["p"], q["n"]): q for q in points}
    if ("singular", 2, 8) in sizes and ("consistent", 2, 8) in sizes:
        s, c = sizes[("singular", 2, 8)], sizes[("consistent", 2, 8)]
        lines.append(
            f"- Discrete S0 + A0 to kappa^{s['order']}, p = 2, n = 8 "
            f"({_scaling_patch([s, c])}): singular mass {_fmt(s['seconds'])} s, consistent "
            f"{_fmt(c['seconds'])} s (in-process).")
    growth = ", ".join(f"{f['mass']} n^{f['exponent']:.2f} (rms {f['residual']:.2f})"
                       for f in fits if f["p"] == 2)
    if growth:
        lines.append(f"- Time against n at p = 2 (least-squares fit): {growth}.")
    if data.get("notes"):
        lines += [f"- Note: {n}" for n in data["notes"]]
    return "\n".join(lines) + "\n"
