#!/usr/bin/env python3
"""Figures and markdown tables of the observer study (scripts/paper2_observer_study.sh).

usage: paper2_observer_study_plot.py STUDY_CSV OUT_DIR

Reads the CSV of robodds-observer-study, writes OUT_DIR/lag_vs_noise.png (noise-free lag on x,
noise floor on y: one curve per sample rate x noise level through the linear gains, a star for
super-twisting, 95 % CI error bars) and OUT_DIR/total_vs_gain.png (RMS error on the noisy signal
against the linear gain w, super-twisting as a dashed line, the Kalman filter at its default q as a
dotted one). Hollow stars in lag_vs_noise.png: super-twisting's lag on the noisy signal,
sqrt(TOTAL^2 - NOISE^2); black-edged diamonds: the Kalman filter (issue 28) through its jerk
densities q. Prints the tables of docs/results/paper2_observer_study.md on stdout.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

NUMERIC = ("rate_hz", "sigma_m", "w_radps", "k1", "k2", "q_m2ps5", "seeds", "lag_rms_mps", "lag_ci95_mps", "noise_rms_mps",
           "noise_ci95_mps", "total_rms_mps", "total_ci95_mps", "total_bias_mps", "restarts_per_run")
SIGNAL_TITLE = {"orbit": "orbit: s = 300 + 60 sin(0.15 t + phase) m", "accel": "accel: s = 300 - 8 t + t^2/2 m"}
RATE_COLOR = {10.0: "tab:red", 50.0: "tab:blue", 100.0: "tab:green"}
SIGMA_MARKER = {0.1: "o", 0.5: "s", 1.0: "^"}


def load(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"paper2_observer_study_plot: {path}: no rows")
    for row in rows:
        for key in NUMERIC:
            row[key] = float(row[key]) if row[key] != "" else math.nan
    return rows


def pick(rows, **where):
    return [r for r in rows if all(r[k] == v for k, v in where.items())]


def values(rows, key):
    return sorted({r[key] for r in rows})


def linear_sorted(rows):
    return sorted((r for r in rows if r["observer"] == "linear"), key=lambda r: r["w_radps"])


def kalman_sorted(rows):
    return sorted((r for r in rows if r["observer"] == "kf"), key=lambda r: r["q_m2ps5"])


KALMAN_DEFAULT_Q = 0.001


def kalman_default(rows):
    return next((r for r in rows if r["observer"] == "kf" and r["q_m2ps5"] == KALMAN_DEFAULT_Q), None)


def sta(rows):
    found = [r for r in rows if r["observer"] == "sta"]
    return found[0] if found else None


def draw_lag_vs_noise(rows, path):
    signals = [s for s in ("orbit", "accel") if pick(rows, signal=s)]
    fig, axes = plt.subplots(1, len(signals), figsize=(7 * len(signals), 6), squeeze=False)
    for ax, signal in zip(axes[0], signals):
        for rate in values(pick(rows, signal=signal), "rate_hz"):
            for sigma in [s for s in values(pick(rows, signal=signal), "sigma_m") if s > 0]:
                group = pick(rows, signal=signal, rate_hz=rate, sigma_m=sigma)
                color = RATE_COLOR.get(rate, "k")
                marker = SIGMA_MARKER.get(sigma, "x")
                lin = linear_sorted(group)
                ax.errorbar([r["lag_rms_mps"] for r in lin], [r["noise_rms_mps"] for r in lin],
                            xerr=[r["lag_ci95_mps"] for r in lin], yerr=[r["noise_ci95_mps"] for r in lin],
                            color=color, marker=marker, markersize=4, linewidth=1,
                            label=f"linear {rate:g} Hz, sigma {sigma:g} m")
                kf = kalman_sorted(group)
                if kf:
                    ax.errorbar([r["lag_rms_mps"] for r in kf], [r["noise_rms_mps"] for r in kf],
                                xerr=[r["lag_ci95_mps"] for r in kf], yerr=[r["noise_ci95_mps"] for r in kf],
                                color=color, marker="D", markersize=5, markeredgecolor="k", linestyle="--",
                                linewidth=1)
                s = sta(group)
                if s is not None:
                    ax.errorbar([s["lag_rms_mps"]], [s["noise_rms_mps"]], xerr=[s["lag_ci95_mps"]],
                                yerr=[s["noise_ci95_mps"]], color=color, marker="*", markersize=14,
                                markeredgecolor="k", linestyle="none")
                    # Under noise the super-twisting observer loses its sliding mode and lags: its
                    # lag on the noisy signal, sqrt(TOTAL^2 - NOISE^2) (for the linear observer this
                    # is its noise-free lag, by superposition), as a hollow star.
                    noisy_lag = math.sqrt(max(0.0, s["total_rms_mps"] ** 2 - s["noise_rms_mps"] ** 2))
                    ax.plot([s["lag_rms_mps"], noisy_lag], [s["noise_rms_mps"]] * 2, color=color, linestyle=":",
                            linewidth=1)
                    ax.plot([noisy_lag], [s["noise_rms_mps"]], marker="*", markersize=14, markerfacecolor="none",
                            markeredgecolor=color, linestyle="none")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("lag: RMS rate error, signal without noise (m/s)")
        ax.set_ylabel("noise floor: RMS rate error, constant range with noise (m/s)")
        ax.set_title(SIGNAL_TITLE.get(signal, signal)
                     + "\nlinear k1 = 2w, k2 = w^2 (w grows leftwards); star: super-twisting;"
                     " diamonds (dashed): Kalman, q grows leftwards"
                     "\nhollow star: super-twisting's lag under noise, sqrt(total^2 - noise^2)", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def draw_total_vs_gain(rows, path):
    signals = [s for s in ("orbit", "accel") if pick(rows, signal=s)]
    rates = values(rows, "rate_hz")
    fig, axes = plt.subplots(len(signals), len(rates), figsize=(5 * len(rates), 4 * len(signals)), squeeze=False)
    for i, signal in enumerate(signals):
        for j, rate in enumerate(rates):
            ax = axes[i][j]
            for k, sigma in enumerate(values(pick(rows, signal=signal, rate_hz=rate), "sigma_m")):
                group = pick(rows, signal=signal, rate_hz=rate, sigma_m=sigma)
                color = f"C{k}"
                lin = linear_sorted(group)
                ax.errorbar([r["w_radps"] for r in lin], [r["total_rms_mps"] for r in lin],
                            yerr=[r["total_ci95_mps"] for r in lin], color=color, marker="o", markersize=3,
                            label=f"linear, sigma {sigma:g} m")
                s = sta(group)
                if s is not None:
                    ax.axhline(s["total_rms_mps"], color=color, linestyle="--", linewidth=1,
                               label=f"super-twisting, sigma {sigma:g} m")
                kf = kalman_default(group)
                if kf is not None:
                    ax.axhline(kf["total_rms_mps"], color=color, linestyle=":", linewidth=1.5,
                               label=f"Kalman q {KALMAN_DEFAULT_Q:g}, sigma {sigma:g} m")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("linear gain w (rad/s): k1 = 2w, k2 = w^2")
            ax.set_ylabel("RMS rate error, signal + noise (m/s)")
            ax.set_title(f"{signal}, {rate:g} Hz", fontsize=9)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def fmt(value, ci=None):
    if math.isnan(value):
        return "-"
    text = f"{value:.3g}" if abs(value) >= 0.01 or value == 0 else f"{value:.2g}"
    if ci is not None and ci >= 0.0005:
        text += f" ± {ci:.1g}"
    return text


def loglog_interp(x, xs, ys):
    """y at x on the piecewise log-log line through (xs, ys), xs increasing; None outside."""
    for (x0, y0), (x1, y1) in zip(zip(xs, ys), zip(xs[1:], ys[1:])):
        if min(x0, x1) <= x <= max(x0, x1) and x0 > 0 and x1 > 0 and y0 > 0 and y1 > 0 and x0 != x1:
            f = (math.log(x) - math.log(x0)) / (math.log(x1) - math.log(x0))
            return math.exp(math.log(y0) + f * (math.log(y1) - math.log(y0)))
    return None


def table_by_observer(rows, signal, columns, key, ci_key=None, title=""):
    """Markdown table: one row per observer, one column per (rate, sigma) in columns."""
    print(title)
    print()
    head = " | ".join(f"{rate:g} Hz" + (f", {sigma:g} m" if sigma is not None else "") for rate, sigma in columns)
    print(f"| observer | {head} |")
    print("|---|" + "---:|" * len(columns))
    first_sigma = columns[0][1] if columns[0][1] is not None else 0.0
    first = pick(rows, signal=signal, rate_hz=columns[0][0], sigma_m=first_sigma)
    observers = ([("sta", None)] + [("linear", r["w_radps"]) for r in linear_sorted(first)]
                 + [("kf", r["q_m2ps5"]) for r in kalman_sorted(first)])
    for name, gain in observers:
        if name == "sta":
            label = "super-twisting (a 2.12, b 2.2, c 1, d 1)"
        elif name == "linear":
            label = f"linear w {gain:g} (k1 {2 * gain:g}, k2 {gain * gain:g})"
        else:
            label = f"Kalman q {gain:g}" + (" (default)" if gain == KALMAN_DEFAULT_Q else "")
        cells = []
        for rate, sigma in columns:
            group = pick(rows, signal=signal, rate_hz=rate, sigma_m=sigma if sigma is not None else 0.0)
            if name == "sta":
                row = sta(group)
            elif name == "linear":
                row = next((r for r in group if r["observer"] == "linear" and r["w_radps"] == gain), None)
            else:
                row = next((r for r in group if r["observer"] == "kf" and r["q_m2ps5"] == gain), None)
            cells.append("-" if row is None else fmt(row[key], row[ci_key] if ci_key else None))
        print(f"| {label} | " + " | ".join(cells) + " |")
    print()


def equal_noise_table(rows, signal):
    print(f"Linear gain with the super-twisting noise floor ({signal} signal; w* interpolated log-log between "
          "the gains of the grid), and the best linear gain of the grid on the noisy signal:")
    print()
    print("| rate | sigma (m) | STA noise floor | w* (rad/s) | linear lag at w* | STA lag | STA total | "
          "best linear w | its total | Kalman total (q 0.001) | best Kalman q | its total |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for rate in values(pick(rows, signal=signal), "rate_hz"):
        for sigma in [s for s in values(pick(rows, signal=signal), "sigma_m") if s > 0]:
            group = pick(rows, signal=signal, rate_hz=rate, sigma_m=sigma)
            s, lin = sta(group), linear_sorted(group)
            ws = [r["w_radps"] for r in lin]
            w_star = loglog_interp(s["noise_rms_mps"], [r["noise_rms_mps"] for r in lin], ws)
            lag_star = loglog_interp(w_star, ws, [r["lag_rms_mps"] for r in lin]) if w_star else None
            best = min(lin, key=lambda r: r["total_rms_mps"])
            kf, kf_default = kalman_sorted(group), kalman_default(group)
            kf_best = min(kf, key=lambda r: r["total_rms_mps"]) if kf else None
            kf_cells = ("- | - | -" if kf_best is None else
                        (fmt(kf_default["total_rms_mps"], kf_default["total_ci95_mps"]) if kf_default else "-")
                        + f" | {kf_best['q_m2ps5']:g} | {fmt(kf_best['total_rms_mps'], kf_best['total_ci95_mps'])}")
            w_text = f"{w_star:.2g}" if w_star else f"outside {ws[0]:g}-{ws[-1]:g}"
            lag_text = fmt(lag_star) if lag_star else "-"
            print(f"| {rate:g} Hz | {sigma:g} | {fmt(s['noise_rms_mps'])} | {w_text} | {lag_text} | "
                  f"{fmt(s['lag_rms_mps'])} | {fmt(s['total_rms_mps'], s['total_ci95_mps'])} | {best['w_radps']:g} | "
                  f"{fmt(best['total_rms_mps'], best['total_ci95_mps'])} | {kf_cells} |")
    print()


def main(argv):
    if len(argv) != 3:
        sys.exit("usage: paper2_observer_study_plot.py STUDY_CSV OUT_DIR")
    rows = load(argv[1])
    out = argv[2]
    os.makedirs(out, exist_ok=True)
    draw_lag_vs_noise(rows, os.path.join(out, "lag_vs_noise.png"))
    draw_total_vs_gain(rows, os.path.join(out, "total_vs_gain.png"))
    rates = values(rows, "rate_hz")
    noisy = [s for s in values(rows, "sigma_m") if s > 0]
    seeds = int(rows[0]["seeds"])
    print(f"({seeds} seeds; mean ± 95 % CI half width over seeds, m/s; CIs below 0.0005 not shown)")
    print()
    for signal in [s for s in ("orbit", "accel") if pick(rows, signal=s)]:
        table_by_observer(rows, signal, [(r, None) for r in rates], "lag_rms_mps", "lag_ci95_mps",
                          f"LAG, {signal}: RMS rate error without noise")
    table_by_observer(rows, "orbit", [(r, s) for r in rates for s in noisy], "noise_rms_mps", "noise_ci95_mps",
                      "NOISE FLOOR: RMS rate error on a constant range with noise")
    for signal in [s for s in ("orbit", "accel") if pick(rows, signal=s)]:
        table_by_observer(rows, signal, [(r, s) for r in rates for s in noisy], "total_rms_mps", "total_ci95_mps",
                          f"TOTAL, {signal}: RMS rate error on the signal with noise")
    if pick(rows, signal="accel"):
        table_by_observer(rows, "accel", [(r, s) for r in rates for s in values(rows, "sigma_m")], "total_bias_mps",
                          None, "BIAS, accel (1 m/s^2): signed mean rate error on the signal with noise "
                          "(the linear observer's lag is -2 a / w whatever the noise)")
    table_by_observer(rows, "orbit", [(r, s) for r in rates for s in noisy], "restarts_per_run", None,
                      "Restarts per run at the default restart rule (restart_sigmas 7 on the estimated noise, floor "
                      "0.5 m; orbit signal with noise; the study itself runs with restarts off)")
    for signal in [s for s in ("orbit", "accel") if pick(rows, signal=s)]:
        equal_noise_table(rows, signal)


if __name__ == "__main__":
    main(sys.argv)
