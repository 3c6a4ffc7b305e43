#!/usr/bin/env python3
"""Figures of a robodds run, after paper 1 (Jun et al. 2021, way-point tracking with a particle filter).

    python3 report.py OUT_DIR

reads the per-topic CSV files that `robodds run SCENARIO --out OUT_DIR` wrote and writes, next to them:

  trajectory.png         (paper Fig. 3) true path, PF estimate, way-points, start, per robot
  velocity.png           (paper Fig. 4) commanded v and omega over time
  distance.png           (paper Fig. 5) distance to the current and to the final way-point over time
  pf_error.png           (paper Fig. 2) x / y error of the PF estimate and of the raw position fixes
  measurement_error.png  as pf_error.png, for runs without estimate_pose.csv (raw fixes only)

and, for paper 2 (Lin & Zhang 2020, range-rate observer; a team circling targets) runs:

  p2_trajectories.png    (paper Fig. 3/5) every robot's path, the targets and their circles
  p2_range_rate.png      (paper Fig. 4/6) per robot, true and observed (super-twisting) range rate
  p2_observer_zoom.png   (paper Fig. 7) true vs super-twisting vs linear range rate over the first 60 s
                         after each target assignment (0 s and each event of mission_target.csv)
  p2_formation.png       radius error and spacing error (gap to the next robot - 360/n deg) over time

The true range rate comes from plant_state.csv and the assigned target (mission_target.csv):
rdot = (p - T) . (v cos theta, v sin theta) / |p - T|. Long runs are decimated for drawing only.

and, for paper 3 (relative localization from UWB arrays and odometry) runs, from the relative pose
files estimate_relative_pose*.csv (one per stage, each row with the true pose of the peer appended):

  p3_relative_trajectory_<i>_<j>.png  (paper Fig. 6/7) robot j in robot i's frame: true and each stage's
                                      estimate (valid rows), one figure per (robot, peer) pair
  p3_relative_error.png               (paper Fig. 8) position and |heading| error over time, per stage,
                                      one column per pair

A figure whose input files are absent is skipped. Prints the path of each written file, one per line.
Exit status: 0 on success (also when no figure had its inputs), 2 when OUT_DIR is missing, holds no CSV
file, or a CSV file is malformed (the one-line message names the file and the column or line), 1 when
numpy / matplotlib cannot be imported.
"""

import csv
import os
import sys
import warnings

import importlib.util

if importlib.util.find_spec("numpy") is None or importlib.util.find_spec("matplotlib") is None:
    # The first python3 on PATH may be another interpreter (pyenv, a venv) without Debian's
    # python3-matplotlib; run this script again with the system one if that is a different program.
    _SYSTEM_PYTHON = "/usr/bin/python3"
    if (__name__ == "__main__" and not os.environ.get("ROBODDS_REPORT_REEXEC")
            and os.path.exists(_SYSTEM_PYTHON)
            and os.path.realpath(sys.executable) != os.path.realpath(_SYSTEM_PYTHON)):
        os.environ["ROBODDS_REPORT_REEXEC"] = "1"
        os.execv(_SYSTEM_PYTHON, [_SYSTEM_PYTHON, os.path.abspath(__file__)] + sys.argv[1:])
    if __name__ == "__main__":
        sys.stderr.write("report: needs numpy and matplotlib (Debian: apt-get install python3-matplotlib), "
                         "not found for %s\n" % sys.executable)
        sys.exit(1)

import numpy as np  # noqa: E402

plt = None  # matplotlib.pyplot, imported by _load_matplotlib() only when there is something to draw
Line2D = None


def _load_matplotlib():
    global plt, Line2D
    if plt is None:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot
        import matplotlib.lines

        plt = matplotlib.pyplot
        Line2D = matplotlib.lines.Line2D


HEADER = ["t_s", "robot_id", "header.step", "header.next_step", "header.stamp_ns"]
HEADER_TARGET = ["t_s", "robot_id", "target_id", "header.step", "header.next_step", "header.stamp_ns"]

# Columns every known file must have (extra columns are ignored). Files not named here are ignored.
SCHEMAS = {
    "plant_state.csv": HEADER + ["x", "y", "theta", "v", "omega"],
    "plant_cmd.csv": HEADER + ["mode", "v", "omega", "v_left", "v_right"],
    "sensor_position.csv": HEADER + ["x", "y", "var_x", "var_y"],
    "sensor_odometry.csv": HEADER + ["v", "omega", "dt_s", "var_v", "var_omega"],
    "estimate_pose.csv": HEADER + ["x", "y", "theta"] + ["cov[%d]" % i for i in range(9)] + ["valid"],
    "control_status.csv": HEADER + ["waypoint_index", "waypoints_total", "waypoints_reached",
                                    "distance_to_waypoint", "distance_to_final", "alpha", "sigma", "done"],
    "mission_waypoints.csv": HEADER + ["waypoints"],
    # Paper 2. Two-part keys (RangeMeasurement, RangeRateEstimate): target_id after robot_id, as the
    # recorder writes the IDL members in order.
    "sensor_range.csv": HEADER_TARGET + ["range", "var"],
    "observer_range_rate.csv": HEADER_TARGET + ["range", "range_rate", "valid", "restarted"],
    "observer_range_rate_linear.csv": HEADER_TARGET + ["range", "range_rate", "valid", "restarted"],
    "mission_target.csv": HEADER + ["active", "target_id", "target_x", "target_y", "desired_radius", "slot",
                                    "team_size"],
}
# Paper 3: the relative estimator's stages, one file each (key robot_id, peer_id; the evaluator appends
# the true pose of the peer in the robot's frame, empty when it had none), in drawing order.
HEADER_PEER = ["t_s", "robot_id", "peer_id", "header.step", "header.next_step", "header.stamp_ns"]
P3_STAGES = [("estimate_relative_pose_odometry.csv", "odometry"), ("estimate_relative_pose_uwb.csv", "uwb"),
             ("estimate_relative_pose_window.csv", "window"),
             ("estimate_relative_pose_pf_baseline.csv", "pf_baseline"), ("estimate_relative_pose.csv", "pf")]
P3_STAGE_COLORS = {"odometry": "C7", "uwb": "C1", "window": "C2", "pf_baseline": "C4", "pf": "C3"}
for _file, _stage in P3_STAGES:
    SCHEMAS[_file] = (HEADER_PEER + ["x", "y", "theta"] + ["cov[%d]" % i for i in range(9)]
                      + ["valid", "true_x", "true_y", "true_theta"])
TEXT_COLUMNS = {"waypoints"}  # parsed separately; every other column is a number
EMPTY_AS_NAN = {"true_x", "true_y", "true_theta"}  # an empty field is NaN (no truth at that step)

MODE_WHEEL_SPEEDS = 1  # idl::CommandMode (VELOCITY = 0, WHEEL_SPEEDS = 1)
DPI = 120


class ReportError(Exception):
    """An input problem; the message is the one line printed before exit status 2."""


# ---- reading ----------------------------------------------------------------------------------

def read_header(path):
    """The stripped fields of the first line; ReportError if unreadable or empty."""
    try:
        with open(path, newline="") as f:
            first = next(csv.reader(f), [])
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        raise ReportError("%s: cannot read: %s" % (path, e))
    if not any(field.strip() for field in first):
        raise ReportError("%s: empty file, no header row" % path)
    return [field.strip() for field in first]


def read_numbers_fast(path, header, columns):
    """numpy's C parser for an all-numeric file (~10x faster than csv on the 100k-row files of a long
    run); None whenever anything is unusual (text, a bad field, a wrong field count, no rows), and
    read_table's checked path then reads the file and names the problem."""
    if any(column in TEXT_COLUMNS for column in header):
        return None
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # "input contained no data" -> the checked path
            values = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2, dtype=float, comments=None)
    except (ValueError, UserWarning, OSError, UnicodeDecodeError):
        return None
    if values.shape[1] != len(header):
        return None
    return {column: values[:, header.index(column)].copy() for column in columns}


def read_table(path, columns):
    """Reads a CSV file into {column: array} (floats; str arrays for TEXT_COLUMNS); checks the columns."""
    name = os.path.basename(path)
    header = read_header(path)
    for column in columns:
        if column not in header:
            raise ReportError("%s: missing column '%s'" % (path, column))
    fast = read_numbers_fast(path, header, columns)
    if fast is not None:
        return fast
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        raise ReportError("%s: cannot read: %s" % (path, e))
    if not rows or not any(field.strip() for field in rows[0]):
        raise ReportError("%s: empty file, no header row" % path)
    header = [field.strip() for field in rows[0]]
    for column in columns:
        if column not in header:
            raise ReportError("%s: missing column '%s'" % (path, column))
    body = [(line, row) for line, row in enumerate(rows[1:], start=2) if row]
    for line, row in body:
        if len(row) != len(header):
            raise ReportError("%s: line %d has %d fields, the header has %d" % (path, line, len(row), len(header)))
    table = {}
    for column in columns:
        index = header.index(column)
        values = [row[index].strip() for _, row in body]
        if column in EMPTY_AS_NAN:
            values = [value or "nan" for value in values]
        if column in TEXT_COLUMNS:
            table[column] = np.array(values, dtype=object)
            continue
        try:
            table[column] = np.array(values, dtype=float) if values else np.zeros(0)
        except ValueError:
            for (line, _), value in zip(body, values):
                try:
                    float(value)
                except ValueError:
                    raise ReportError("%s: line %d, column '%s': not a number: '%s'" % (path, line, column, value))
            raise ReportError("%s: column '%s': not a number" % (name, column))  # not reached
    return table


def load(out_dir):
    """Reads every known CSV file of out_dir: {file name: table}. Raises ReportError on bad input."""
    if not os.path.isdir(out_dir):
        raise ReportError("%s: no such directory" % out_dir)
    csv_files = sorted(f for f in os.listdir(out_dir) if f.endswith(".csv"))
    if not csv_files:
        raise ReportError("%s: no CSV file (expected the output of `robodds run SCENARIO --out DIR`)" % out_dir)
    return {f: read_table(os.path.join(out_dir, f), SCHEMAS[f]) for f in csv_files if f in SCHEMAS}


def by_robot(table):
    """Splits a table into {robot_id: table}, rows of each robot in step order."""
    groups = {}
    if table is None or len(table["robot_id"]) == 0:
        return groups
    ids = table["robot_id"].astype(np.int64)
    for robot in sorted(set(ids.tolist())):
        rows = np.flatnonzero(ids == robot)
        rows = rows[np.argsort(table["header.step"][rows], kind="stable")]
        groups[robot] = {column: values[rows] for column, values in table.items()}
    return groups


def parse_waypoints(text):
    """'x:y;x:y;...' -> (n, 2) array (m)."""
    points = []
    for item in str(text).split(";"):
        item = item.strip()
        if not item:
            continue
        parts = item.split(":")
        if len(parts) != 2:
            raise ValueError("way-point '%s' is not x:y" % item)
        points.append((float(parts[0]), float(parts[1])))
    return np.array(points, dtype=float).reshape(-1, 2)


def waypoints_by_robot(table, path):
    """Last published mission of each robot: {robot_id: (n, 2) array}."""
    missions = {}
    for robot, rows in by_robot(table).items():
        if len(rows["waypoints"]) == 0:
            continue
        try:
            missions[robot] = parse_waypoints(rows["waypoints"][-1])
        except ValueError as e:
            raise ReportError("%s: column 'waypoints': %s" % (path, e))
    return missions


def match_steps(truth, other):
    """Indices (i_truth, i_other) of the rows of two step-sorted tables with equal header.step."""
    truth_steps = truth["header.step"]
    other_steps = other["header.step"]
    if len(truth_steps) == 0 or len(other_steps) == 0:
        return np.zeros(0, dtype=int), np.zeros(0, dtype=int)
    pos = np.clip(np.searchsorted(truth_steps, other_steps), 0, len(truth_steps) - 1)
    hit = truth_steps[pos] == other_steps
    return pos[hit], np.flatnonzero(hit)


def valid_rows(estimate):
    keep = estimate["valid"] != 0
    return {column: values[keep] for column, values in estimate.items()}


# ---- figures ----------------------------------------------------------------------------------

def robot_colors(robots):
    cycle = plt.rcParams["axes.prop_cycle"].by_key().get("color", ["C0"])
    return {robot: cycle[i % len(cycle)] for i, robot in enumerate(sorted(robots))}


def save(fig, out_dir, name, written):
    path = os.path.join(out_dir, name)
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    print(path)
    written.append(path)


def save_world_plot(fig, ax, handles, title, out_dir, name, written):
    """Legend, equal axes in world metres, title and grid of an x-y plot, then save() it."""
    ax.legend(handles=handles, loc="best", fontsize=8, framealpha=0.85)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    save(fig, out_dir, name, written)

def plot_trajectory(data, missions, out_dir, written):
    truth = by_robot(data.get("plant_state.csv"))
    estimate = {r: valid_rows(t) for r, t in by_robot(data.get("estimate_pose.csv")).items()}
    robots = sorted(set(truth) | set(estimate))
    if not robots:
        return
    colors = robot_colors(set(robots) | set(missions))
    fig, ax = plt.subplots(figsize=(7.5, 7.0))
    for robot in sorted(set(robots) | set(missions)):
        c = colors[robot]
        if robot in truth and len(truth[robot]["x"]):
            t = truth[robot]
            ax.plot(t["x"], t["y"], "-", color=c, lw=1.6)
        if robot in estimate and len(estimate[robot]["x"]):
            e = estimate[robot]
            ax.plot(e["x"], e["y"], "--", color=c, lw=1.2)
        start = truth.get(robot) if robot in truth and len(truth[robot]["x"]) else estimate.get(robot)
        if start is not None and len(start["x"]):
            ax.plot(start["x"][0], start["y"][0], "o", ms=9, mfc=c, mec="black", zorder=5)
        if robot in missions and len(missions[robot]):
            wp = missions[robot]
            ax.plot(wp[:, 0], wp[:, 1], "^", ms=10, mfc="none", mec=c, mew=1.8, zorder=6)
            for i, (x, y) in enumerate(wp, start=1):
                ax.annotate(str(i), (x, y), xytext=(6, 6), textcoords="offset points", color=c, fontsize=9,
                            fontweight="bold", zorder=7,
                            bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.75))
    handles = [Line2D([], [], color=colors[r], lw=2, label="robot %d" % r) for r in sorted(colors)]
    handles.append(Line2D([], [], color="gray", ls="-", label="true path"))
    if estimate:
        handles.append(Line2D([], [], color="gray", ls="--", label="estimate"))
    if missions:
        handles.append(Line2D([], [], color="gray", ls="none", marker="^", mfc="none", ms=9, label="way-point (order)"))
    handles.append(Line2D([], [], color="gray", ls="none", marker="o", mec="black", ms=8, label="start"))
    save_world_plot(fig, ax, handles, "Trajectory (paper Fig. 3)", out_dir, "trajectory.png", written)


def command_twist(cmd, state):
    """Commanded (v, omega) of one robot. WHEEL_SPEEDS rows give v = (v_left + v_right) / 2; their omega needs
    the wheel base, which is not recorded, so the plant's achieved omega at the same step stands in (NaN if none)."""
    v = cmd["v"].copy()
    omega = cmd["omega"].copy()
    wheels = cmd["mode"] == MODE_WHEEL_SPEEDS
    if np.any(wheels):
        v[wheels] = 0.5 * (cmd["v_left"][wheels] + cmd["v_right"][wheels])
        omega[wheels] = np.nan
        if state is not None:
            i_state, i_cmd = match_steps(state, cmd)
            take = wheels[i_cmd]
            omega[i_cmd[take]] = state["omega"][i_state[take]]
    return v, omega


def plot_velocity(data, out_dir, written):
    cmds = by_robot(data.get("plant_cmd.csv"))
    if not cmds:
        return
    states = by_robot(data.get("plant_state.csv"))
    colors = robot_colors(cmds)
    fig, (ax_v, ax_w) = plt.subplots(2, 1, sharex=True, figsize=(8.0, 6.0))
    for robot, cmd in cmds.items():
        v, omega = command_twist(cmd, states.get(robot))
        ax_v.plot(cmd["t_s"], v, color=colors[robot], lw=1.3, drawstyle="steps-post", label="robot %d" % robot)
        ax_w.plot(cmd["t_s"], omega, color=colors[robot], lw=1.3, drawstyle="steps-post", label="robot %d" % robot)
    ax_v.set_ylabel("v [m/s]")
    ax_w.set_ylabel(r"$\omega$ [rad/s]")
    ax_w.set_xlabel("time [s]")
    ax_v.set_title("Commanded velocities (paper Fig. 4)")
    for ax in (ax_v, ax_w):
        ax.grid(True, alpha=0.3)
        ax.axhline(0.0, color="black", lw=0.6)
    ax_v.legend(loc="best", fontsize=8)
    fig.tight_layout()
    save(fig, out_dir, "velocity.png", written)


def plot_distance(data, out_dir, written):
    status = by_robot(data.get("control_status.csv"))
    if not status:
        return
    colors = robot_colors(status)
    fig, (ax_wp, ax_final) = plt.subplots(2, 1, sharex=True, figsize=(8.0, 6.0))
    any_reached = False
    for robot, s in status.items():
        c = colors[robot]
        ax_wp.plot(s["t_s"], s["distance_to_waypoint"], color=c, lw=1.3, label="robot %d" % robot)
        ax_final.plot(s["t_s"], s["distance_to_final"], color=c, lw=1.3, label="robot %d" % robot)
        # Mark each way-point reached (waypoints_reached goes up) on the upper plot.
        up = np.flatnonzero(np.diff(s["waypoints_reached"]) > 0) + 1
        if len(up):
            ax_wp.plot(s["t_s"][up], s["distance_to_waypoint"][up - 1], "v", color=c, ms=6, ls="none")
            any_reached = True
    ax_wp.set_ylabel("to current way-point [m]")
    ax_final.set_ylabel("to final way-point [m]")
    ax_final.set_xlabel("time [s]")
    ax_wp.set_title("Distance to the way-points (paper Fig. 5)")
    for ax in (ax_wp, ax_final):
        ax.grid(True, alpha=0.3)
        ax.set_ylim(bottom=0.0)
    handles = [Line2D([], [], color=colors[r], lw=1.5, label="robot %d" % r) for r in sorted(status)]
    if any_reached:
        handles.append(Line2D([], [], color="gray", ls="none", marker="v", ms=6, label="way-point reached"))
    ax_wp.legend(handles=handles, loc="best", fontsize=8)
    fig.tight_layout()
    save(fig, out_dir, "distance.png", written)


def rmse(values):
    values = values[np.isfinite(values)]
    return float(np.sqrt(np.mean(values * values))) if len(values) else float("nan")


def plot_errors(data, out_dir, written):
    """pf_error.png (estimate and raw fixes vs truth) or, without estimate_pose.csv, measurement_error.png."""
    truth = by_robot(data.get("plant_state.csv"))
    if not truth:
        return
    has_estimate = "estimate_pose.csv" in data
    estimates = {r: valid_rows(t) for r, t in by_robot(data.get("estimate_pose.csv")).items()}
    fixes = by_robot(data.get("sensor_position.csv"))
    if not has_estimate and "sensor_position.csv" not in data:
        return
    colors = robot_colors(set(truth) | set(estimates) | set(fixes))
    fig, axes = plt.subplots(2, 1, sharex=True, figsize=(8.0, 6.5))
    for robot in sorted(colors):
        if robot not in truth:
            continue
        c = colors[robot]
        for source, rows in (("measurement", fixes.get(robot)), ("estimate", estimates.get(robot))):
            if rows is None:
                continue
            i_truth, i_rows = match_steps(truth[robot], rows)
            if not len(i_rows):
                continue
            t = rows["t_s"][i_rows]
            for ax, axis in zip(axes, ("x", "y")):
                err = rows[axis][i_rows] - truth[robot][axis][i_truth]
                label = "robot %d %s (RMSE %.3g m)" % (robot, source, rmse(err))
                if source == "measurement":
                    ax.plot(t, err, ".", color=c, ms=3.5, alpha=0.45, label=label)
                else:
                    ax.plot(t, err, "-", color=c, lw=1.5, label=label)
    for ax, axis in zip(axes, ("x", "y")):
        ax.set_ylabel("%s error [m]" % axis)
        ax.axhline(0.0, color="black", lw=0.6)
        ax.grid(True, alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="upper right", fontsize=7, framealpha=0.85)
    axes[1].set_xlabel("time [s]")
    if has_estimate:
        axes[0].set_title("Estimate (PF) and raw measurement error vs truth (paper Fig. 2)")
        name = "pf_error.png"
    else:
        axes[0].set_title("Raw position measurement error vs truth")
        name = "measurement_error.png"
    fig.tight_layout()
    save(fig, out_dir, name, written)


# ---- paper 2: circumnavigation with range-rate observers ---------------------------------------

MAX_DRAWN_POINTS = 4000  # per line; long runs (100k rows per robot) are decimated for drawing only
ZOOM_WINDOW_S = 60.0
MAX_ZOOM_WINDOWS = 4


def drawn(n):
    """Index slice that keeps at most MAX_DRAWN_POINTS of n rows, evenly spaced."""
    return slice(None, None, max(1, -(-n // MAX_DRAWN_POINTS)))


def target_schedule(table):
    """mission_target.csv -> {robot_id: rows in step order}: the robot's assignments (active, target_id,
    target_x, target_y, desired_radius, ...), each valid from its header.step to the next one's."""
    return by_robot(table)


def assignment_index(schedule, steps):
    """For each step, the row of the robot's schedule in force (-1 before its first assignment)."""
    if schedule is None or len(schedule["header.step"]) == 0:
        return np.full(len(steps), -1, dtype=int)
    return np.searchsorted(schedule["header.step"], steps, side="right") - 1


def truth_to_target(state, schedule):
    """True range and range rate of one robot to its assigned target, per plant_state row:
    {t_s, step, x, y, active, target_id, target_x, target_y, desired_radius, range, range_rate, bearing}; rows
    without an active assignment have NaN range, range rate and bearing."""
    steps = state["header.step"]
    i = assignment_index(schedule, steps)
    has = i >= 0
    take = np.where(has, i, 0)

    def field(name, missing):
        if schedule is None or len(schedule["header.step"]) == 0:
            return np.full(len(steps), missing, dtype=float)
        return np.where(has, schedule[name][take], missing)

    active = field("active", 0.0) != 0
    tx, ty = field("target_x", np.nan), field("target_y", np.nan)
    dx, dy = state["x"] - tx, state["y"] - ty
    rng = np.hypot(dx, dy)
    with np.errstate(invalid="ignore", divide="ignore"):
        rdot = (dx * state["v"] * np.cos(state["theta"]) + dy * state["v"] * np.sin(state["theta"])) / rng
    nan = np.full(len(steps), np.nan)
    return {"t_s": state["t_s"], "step": steps, "x": state["x"], "y": state["y"], "active": active,
            "target_id": field("target_id", -1.0), "target_x": tx, "target_y": ty,
            "desired_radius": field("desired_radius", np.nan),
            "range": np.where(active, rng, nan), "range_rate": np.where(active, rdot, nan),
            "bearing": np.where(active, np.arctan2(dy, dx), nan)}


def spacing_errors(truths):
    """Angular spacing error (rad) of each robot: its gap to the next robot counter-clockwise around the
    same target minus 2 pi / n, n the robots active on that target at that step (NaN when alone or
    inactive). truths: {robot: truth_to_target(...)}; returns ({robot: error array per its rows}, steps)."""
    robots = sorted(truths)
    steps = np.unique(np.concatenate([truths[r]["step"] for r in robots])) if robots else np.zeros(0)
    count = len(steps)
    bearing = np.full((count, len(robots)), np.nan)
    target = np.full((count, len(robots)), -1.0)
    for j, r in enumerate(robots):
        rows = np.searchsorted(steps, truths[r]["step"])
        bearing[rows, j] = truths[r]["bearing"]
        target[rows, j] = np.where(truths[r]["active"], truths[r]["target_id"], -1.0)
    error = np.full((count, len(robots)), np.nan)
    for tid in np.unique(target[target >= 0]):
        angles = np.where((target == tid) & np.isfinite(bearing), bearing, np.nan)
        n = np.sum(np.isfinite(angles), axis=1)
        order = np.argsort(angles, axis=1)  # NaN last
        ordered = np.take_along_axis(angles, order, axis=1)
        k = np.arange(len(robots))[None, :]
        nxt = np.where(k + 1 < n[:, None], k + 1, 0)
        gap = np.take_along_axis(ordered, nxt, axis=1) - ordered
        gap = np.where(nxt == 0, gap + 2.0 * np.pi, gap)
        with np.errstate(invalid="ignore", divide="ignore"):
            err_sorted = np.where((k < n[:, None]) & (n[:, None] >= 2), gap - 2.0 * np.pi / n[:, None], np.nan)
        rows = np.nonzero(np.isfinite(err_sorted))
        error[rows[0], order[rows]] = err_sorted[rows]
    return {r: error[np.searchsorted(steps, truths[r]["step"]), j] for j, r in enumerate(robots)}


def assignment_starts(schedules):
    """Times (s) at which some robot gets a new active assignment (its first one, or another target):
    the starts of the observer zoom windows, sorted, at most MAX_ZOOM_WINDOWS."""
    starts = set()
    for rows in schedules.values():
        previous = None
        for t, active, tid in zip(rows["t_s"], rows["active"], rows["target_id"]):
            current = tid if active != 0 else None
            if current is not None and current != previous:
                starts.add(round(float(t), 6))
            previous = current
    return sorted(starts)[:MAX_ZOOM_WINDOWS]


def masked_estimate(rows):
    """(t_s, range_rate with invalid samples as NaN, restart times) of one robot's observer rows."""
    rate = np.where(rows["valid"] != 0, rows["range_rate"], np.nan)
    return rows["t_s"], rate, rows["t_s"][rows["restarted"] != 0]


def paper2_truths(data):
    states = by_robot(data.get("plant_state.csv"))
    schedules = target_schedule(data.get("mission_target.csv"))
    if not states or not schedules:
        return {}, schedules
    return {r: truth_to_target(states[r], schedules.get(r)) for r in states}, schedules


def plot_p2_trajectories(data, truths, schedules, out_dir, written):
    if not truths:
        return
    colors = robot_colors(truths)
    fig, ax = plt.subplots(figsize=(7.5, 7.0))
    for robot, tr in truths.items():
        c = colors[robot]
        d = drawn(len(tr["x"]))
        ax.plot(tr["x"][d], tr["y"][d], "-", color=c, lw=1.2, label="robot %d" % robot)
        if len(tr["x"]):
            ax.plot(tr["x"][0], tr["y"][0], "o", ms=8, mfc=c, mec="black", zorder=5)
            ax.plot(tr["x"][-1], tr["y"][-1], "s", ms=6, mfc=c, mec="black", zorder=5)
    targets = {}
    for rows in schedules.values():
        for active, tid, x, y, radius in zip(rows["active"], rows["target_id"], rows["target_x"], rows["target_y"],
                                             rows["desired_radius"]):
            if active != 0:
                targets[int(tid)] = (x, y, radius)
    circle = np.linspace(0.0, 2.0 * np.pi, 361)
    for tid, (x, y, radius) in sorted(targets.items()):
        ax.plot(x, y, "kx", ms=10, mew=2, zorder=6)
        ax.plot(x + radius * np.cos(circle), y + radius * np.sin(circle), "k:", lw=1.0)
        ax.annotate("target %d" % tid, (x, y), xytext=(6, 6), textcoords="offset points", fontsize=9)
    handles = [Line2D([], [], color=colors[r], lw=2, label="robot %d" % r) for r in sorted(colors)]
    handles += [Line2D([], [], color="gray", ls="none", marker="o", mec="black", ms=7, label="start"),
                Line2D([], [], color="gray", ls="none", marker="s", mec="black", ms=6, label="end"),
                Line2D([], [], color="black", ls=":", marker="x", label="target, desired radius")]
    save_world_plot(fig, ax, handles, "Trajectories around the targets (paper 2 Fig. 3/5)", out_dir, "p2_trajectories.png",
                    written)


def plot_p2_range_rate(data, truths, out_dir, written):
    estimates = by_robot(data.get("observer_range_rate.csv"))
    if not estimates:
        return
    robots = sorted(set(estimates) | set(truths))
    colors = robot_colors(robots)
    fig, axes = plt.subplots(len(robots), 1, sharex=True, figsize=(9.0, 2.2 * len(robots) + 0.8), squeeze=False)
    for ax, robot in zip(axes[:, 0], robots):
        if robot in truths:
            tr = truths[robot]
            d = drawn(len(tr["t_s"]))
            ax.plot(tr["t_s"][d], tr["range_rate"][d], "-", color="black", lw=1.0, label="true")
        if robot in estimates:
            t, rate, restarts = masked_estimate(estimates[robot])
            d = drawn(len(t))
            ax.plot(t[d], rate[d], "-", color=colors[robot], lw=0.9, alpha=0.85, label="super-twisting (valid)")
            for i, tr_s in enumerate(restarts):
                ax.axvline(tr_s, color="gray", ls=":", lw=1.0, label="restart" if i == 0 else None)
        ax.set_ylabel("robot %d\nrange rate [m/s]" % robot, fontsize=8)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right", fontsize=7, framealpha=0.85)
    axes[-1, 0].set_xlabel("time [s]")
    axes[0, 0].set_title("True and observed range rate (paper 2 Fig. 4/6)")
    fig.tight_layout()
    save(fig, out_dir, "p2_range_rate.png", written)


def plot_p2_observer_zoom(data, truths, schedules, out_dir, written):
    sta = by_robot(data.get("observer_range_rate.csv"))
    linear = by_robot(data.get("observer_range_rate_linear.csv"))
    if not sta and not linear:
        return
    starts = assignment_starts(schedules) or [0.0]
    robots = sorted(set(sta) | set(linear))
    fig, axes = plt.subplots(len(robots), len(starts), figsize=(4.5 * len(starts) + 1.0, 2.2 * len(robots) + 0.8),
                             squeeze=False)
    for i, robot in enumerate(robots):
        for j, start in enumerate(starts):
            ax = axes[i, j]
            end = start + ZOOM_WINDOW_S
            drew = False
            if robot in truths:
                tr = truths[robot]
                keep = (tr["t_s"] >= start) & (tr["t_s"] < end) & np.isfinite(tr["range_rate"])
                drew = drew or bool(np.any(keep))
                d = drawn(int(np.sum(keep)))
                ax.plot(tr["t_s"][keep][d], tr["range_rate"][keep][d], "-", color="black", lw=1.2, label="true")
            for rows_by_robot, color, label in ((sta, "C0", "super-twisting"), (linear, "C1", "linear")):
                if robot not in rows_by_robot:
                    continue
                t, rate, _ = masked_estimate(rows_by_robot[robot])
                keep = (t >= start) & (t < end)
                drew = drew or bool(np.any(keep))
                d = drawn(int(np.sum(keep)))
                ax.plot(t[keep][d], rate[keep][d], "-", color=color, lw=1.0, label=label)
            if not drew:
                ax.text(0.5, 0.5, "no target", transform=ax.transAxes, ha="center", va="center", color="gray")
            ax.set_xlim(start, end)
            ax.grid(True, alpha=0.3)
            if j == 0:
                ax.set_ylabel("robot %d\nrange rate [m/s]" % robot, fontsize=8)
            if i == 0:
                ax.set_title("%g-%g s" % (start, end), fontsize=9)
            if i == len(robots) - 1:
                ax.set_xlabel("time [s]")
    axes[0, 0].legend(loc="best", fontsize=7, framealpha=0.85)
    fig.suptitle("True vs super-twisting vs linear range rate after each assignment (paper 2 Fig. 7)", fontsize=10)
    fig.tight_layout()
    save(fig, out_dir, "p2_observer_zoom.png", written)


def plot_p2_formation(truths, out_dir, written):
    if not truths:
        return
    spacing = spacing_errors(truths)
    colors = robot_colors(truths)
    fig, (ax_r, ax_s) = plt.subplots(2, 1, sharex=True, figsize=(9.0, 6.0))
    for robot, tr in truths.items():
        d = drawn(len(tr["t_s"]))
        ax_r.plot(tr["t_s"][d], (tr["range"] - tr["desired_radius"])[d], color=colors[robot], lw=1.0,
                  label="robot %d" % robot)
        ax_s.plot(tr["t_s"][d], np.degrees(spacing[robot])[d], color=colors[robot], lw=1.0, label="robot %d" % robot)
    ax_r.set_ylabel("radius error [m]")
    ax_s.set_ylabel("spacing error [deg]\n(gap to next - 360/n)")
    ax_s.set_xlabel("time [s]")
    ax_r.set_title("Formation: distance to the target minus the desired radius, angular spacing")
    for ax in (ax_r, ax_s):
        ax.grid(True, alpha=0.3)
        ax.axhline(0.0, color="black", lw=0.6)
        ax.legend(loc="upper right", fontsize=7)
        ax.set_yscale("symlog", linthresh=1.0)
    fig.tight_layout()
    save(fig, out_dir, "p2_formation.png", written)


def plot_paper2(data, out_dir, written):
    truths, schedules = paper2_truths(data)
    plot_p2_trajectories(data, truths, schedules, out_dir, written)
    plot_p2_range_rate(data, truths, out_dir, written)
    plot_p2_observer_zoom(data, truths, schedules, out_dir, written)
    plot_p2_formation(truths, out_dir, written)


# ---- paper 3: relative poses from UWB arrays and odometry ---------------------------------------

def by_pair(table):
    """Splits a relative pose table into {(robot_id, peer_id): table}, rows of each pair in step order."""
    groups = {}
    if table is None or len(table["robot_id"]) == 0:
        return groups
    keys = table["robot_id"].astype(np.int64) * (1 << 32) + table["peer_id"].astype(np.int64)
    for key in sorted(set(keys.tolist())):
        rows = np.flatnonzero(keys == key)
        rows = rows[np.argsort(table["header.step"][rows], kind="stable")]
        groups[(key >> 32, key & 0xffffffff)] = {column: values[rows] for column, values in table.items()}
    return groups


def wrap_angle(a):
    """Angles wrapped to [-pi, pi)."""
    return (a + np.pi) % (2.0 * np.pi) - np.pi


def relative_errors(rows):
    """(t_s, position error m, |heading error| deg) of the valid rows with a truth, as the evaluator's
    metrics.stages take them (heading wrapped)."""
    keep = (rows["valid"] != 0) & np.isfinite(rows["true_x"]) & np.isfinite(rows["true_theta"])
    position = np.hypot(rows["x"][keep] - rows["true_x"][keep], rows["y"][keep] - rows["true_y"][keep])
    heading = np.degrees(np.abs(wrap_angle(rows["theta"][keep] - rows["true_theta"][keep])))
    return rows["t_s"][keep], position, heading


def paper3_stages(data):
    """[(stage, {(robot, peer): rows})] of the relative pose files present, in P3_STAGES order."""
    return [(stage, by_pair(data[name])) for name, stage in P3_STAGES if name in data]


def plot_p3_trajectories(stages, out_dir, written):
    pairs = sorted(set(pair for _, by in stages for pair in by))
    for robot, peer in pairs:
        fig, ax = plt.subplots(figsize=(7.0, 6.5))
        # The truth of the stage file with the most of it (every file carries it for its own rows).
        truths = [by[(robot, peer)] for _, by in stages if (robot, peer) in by]
        truth = max(truths, key=lambda rows: int(np.sum(np.isfinite(rows["true_x"]))))
        handles = []
        for stage, by in stages:
            rows = by.get((robot, peer))
            if rows is None:
                continue
            keep = rows["valid"] != 0
            d = drawn(int(np.sum(keep)))
            color = P3_STAGE_COLORS[stage]
            if stage == "uwb":  # single epochs: a cloud, not a path
                ax.plot(rows["x"][keep][d], rows["y"][keep][d], ".", color=color, ms=2.0, alpha=0.5)
                handles.append(Line2D([], [], color=color, ls="none", marker=".", ms=6, label=stage))
            else:
                ax.plot(rows["x"][keep][d], rows["y"][keep][d], "-", color=color, lw=1.0, alpha=0.9)
                handles.append(Line2D([], [], color=color, lw=1.5, label=stage))
        d = drawn(len(truth["true_x"]))
        ax.plot(truth["true_x"][d], truth["true_y"][d], "-", color="black", lw=1.6, zorder=4)
        ax.plot(0.0, 0.0, "^", ms=10, mfc="white", mec="black", zorder=6)
        handles = [Line2D([], [], color="black", lw=1.6, label="true")] + handles
        handles.append(Line2D([], [], color="black", ls="none", marker="^", mfc="white", ms=8,
                              label="robot %d (origin, facing +x)" % robot))
        save_world_plot(fig, ax, handles, "Robot %d in robot %d's frame: true and estimated (paper 3 Fig. 6/7)"
                        % (peer, robot), out_dir, "p3_relative_trajectory_%d_%d.png" % (robot, peer), written)


def plot_p3_errors(stages, out_dir, written):
    pairs = sorted(set(pair for _, by in stages for pair in by))
    if not pairs:
        return
    fig, axes = plt.subplots(2, len(pairs), sharex=True, figsize=(5.0 * len(pairs) + 1.5, 6.0), squeeze=False)
    for column, pair in enumerate(pairs):
        ax_p, ax_h = axes[0, column], axes[1, column]
        for stage, by in stages:
            if pair not in by:
                continue
            t, position, heading = relative_errors(by[pair])
            d = drawn(len(t))
            color = P3_STAGE_COLORS[stage]
            ax_p.plot(t[d], position[d], "-", color=color, lw=0.9, label=stage)
            ax_h.plot(t[d], heading[d], "-", color=color, lw=0.9, label=stage)
        ax_p.set_title("robot %d -> peer %d" % pair, fontsize=9)
        ax_h.set_xlabel("time [s]")
        for ax in (ax_p, ax_h):
            ax.grid(True, alpha=0.3)
            ax.set_ylim(bottom=0.0)
    axes[0, 0].set_ylabel("position error [m]")
    axes[1, 0].set_ylabel("|heading error| [deg]")
    if axes[0, 0].get_legend_handles_labels()[0]:
        axes[0, 0].legend(loc="upper right", fontsize=7, framealpha=0.85)
    fig.suptitle("Relative pose error per stage (paper 3 Fig. 8)", fontsize=10)
    fig.tight_layout()
    save(fig, out_dir, "p3_relative_error.png", written)


def plot_paper3(data, out_dir, written):
    stages = paper3_stages(data)
    plot_p3_trajectories(stages, out_dir, written)
    plot_p3_errors(stages, out_dir, written)


def report(out_dir):
    """Writes the figures of out_dir; returns the written paths. Raises ReportError on bad input."""
    data = load(out_dir)
    # Every input check happens before the first figure, so bad input leaves no figure behind.
    missions = waypoints_by_robot(data.get("mission_waypoints.csv"), os.path.join(out_dir, "mission_waypoints.csv"))
    written = []
    if data:
        _load_matplotlib()
    plot_trajectory(data, missions, out_dir, written)
    plot_velocity(data, out_dir, written)
    plot_distance(data, out_dir, written)
    plot_errors(data, out_dir, written)
    plot_paper2(data, out_dir, written)
    plot_paper3(data, out_dir, written)
    return written


def main(argv):
    if len(argv) != 1 or argv[0] in ("-h", "--help"):
        sys.stderr.write("usage: report.py OUT_DIR   (the --out directory of `robodds run`)\n")
        return 2
    try:
        written = report(argv[0])
    except ReportError as e:
        sys.stderr.write("report: %s\n" % e)
        return 2
    if not written:
        sys.stderr.write("report: %s: no figure has its input files, nothing written\n" % argv[0])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
