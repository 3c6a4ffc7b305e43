#!/usr/bin/env python3
"""Figures of a robodds run.

    python3 report.py OUT_DIR

reads the per-topic CSV files that `robodds run SCENARIO --out OUT_DIR` wrote (and its summary.json, when
there is one) and writes, next to them:

  trajectory.png         true path, estimate, way-points, start, per robot
  velocity.png           commanded v and omega over time
  distance.png           distance to the current and to the final way-point over time (a gap where the
                         controller had no valid estimate, so no distance)
  pf_error.png           x / y error of the estimate and of the raw position fixes, with summary.json's
                         2-D RMSEs in the legend
  measurement_error.png  as pf_error.png, for runs without estimate_pose.csv (raw fixes only)

and, for paper 2 (Lin & Zhang 2020, range-rate observer; a team circling targets) runs:

  p2_trajectories.png    every robot's path, the targets and their circles
  p2_range_rate.png      per robot, true and observed (super-twisting) range rate
  p2_observer_zoom.png   true vs super-twisting vs linear range rate over the first 60 s after each
                         target assignment (0 s and each event of mission_target.csv); a panel with
                         nothing to show says why (the robot left, no target)
  p2_formation.png       radius error and spacing error (gap to the next robot - 360/n deg) over time

The true range rate comes from plant_state.csv and the assigned target (mission_target.csv):
rdot = (p - T) . (v cos theta, v sin theta) / |p - T|. Long runs are decimated for drawing only.

and, for paper 3 (relative localization from UWB arrays and odometry) runs, from the relative pose
files estimate_relative_pose*.csv (one per stage, each row with the true pose of the peer appended):

  p3_relative_trajectory_<i>_<j>.png  robot j in robot i's frame: true and each stage's estimate (valid
                                      rows), one figure per (robot, peer) pair
  p3_relative_error.png               position and |heading| error over time, per stage, one column per pair

Each figure is titled with what it shows and, below, the scenario's name and description (summary.json);
the paper's figure is named only for the scenarios that reproduce it (PAPER_FIGURES). Time axes start at
the run's start (real-time runs stamp samples with the wall clock). The figures are drawn in parallel
worker processes (ROBODDS_REPORT_JOBS, default: one per idle processor).

A figure whose input files are absent is skipped. Prints the path of each written file, one per line.
Exit status: 0 on success (also when no figure had its inputs), 2 when OUT_DIR is missing, holds no CSV
file, or a CSV file or summary.json is malformed (the one-line message names the file and the column,
key or line), 1 when numpy / matplotlib cannot be imported.
"""

import csv
import json
import math
import os
import sys
import textwrap
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

# matplotlib, imported by _load_matplotlib() only when there is something to draw: the Figure class with
# the Agg canvas directly (no pyplot: no figure manager, no GUI backend probing).
Figure = None
FigureCanvasAgg = None
Line2D = None
Patch = None
matplotlib = None


def _load_matplotlib():
    global Figure, FigureCanvasAgg, Line2D, Patch, matplotlib
    if Figure is None:
        import matplotlib as _matplotlib

        _matplotlib.use("Agg")
        from matplotlib.backends.backend_agg import FigureCanvasAgg as _canvas
        from matplotlib.figure import Figure as _figure
        from matplotlib.lines import Line2D as _line
        from matplotlib.patches import Patch as _patch

        matplotlib, Figure, FigureCanvasAgg, Line2D, Patch = _matplotlib, _figure, _canvas, _line, _patch


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
# Read when the file has them (runs recorded before the column existed lack it).
OPTIONAL_COLUMNS = {"control_status.csv": ["state"]}
# No figure draws these: only their header is checked (reading 2 MB of odometry cost ~10 % of the report).
HEADER_ONLY = {"sensor_odometry.csv", "sensor_range.csv"}
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
# idl::ControlState: the controller computed the distances only while TRACKING or DONE; in the other
# states (NO_MISSION 1, NO_ESTIMATE 2, ESTIMATE_INVALID 3, ESTIMATE_STALE 4) control/status carries 0.
STATE_TRACKING = 0
STATE_DONE = 5
DPI = 120
PNG_COMPRESS_LEVEL = 3

# The paper figure each figure reproduces, only for the scenarios that are that figure's setting (the
# same robot on other missions, or a user's scenario, is no paper figure). Keys: figure names without
# .png (p3_relative_trajectory stands for every pair's file).
PAPER_FIGURES = {
    "paper1_ideal": {"trajectory": "paper 1 Fig. 3", "velocity": "paper 1 Fig. 4", "distance": "paper 1 Fig. 5"},
    "paper1_waypoints": {"trajectory": "paper 1 Fig. 3", "velocity": "paper 1 Fig. 4", "distance": "paper 1 Fig. 5",
                         "pf_error": "paper 1 Fig. 2"},
    "paper2_circumnavigation": {"p2_trajectories": "paper 2 Fig. 3", "p2_range_rate": "paper 2 Fig. 4",
                                "p2_observer_zoom": "paper 2 Fig. 7"},
    "paper2_circumnavigation_noise": {"p2_trajectories": "paper 2 Fig. 5", "p2_range_rate": "paper 2 Fig. 6"},
    "paper3_exp1a": {"p3_relative_trajectory": "paper 3 Fig. 7"},
    "paper3_exp1b": {"p3_relative_trajectory": "paper 3 Fig. 6"},
    "paper3_exp2": {"p3_relative_trajectory": "paper 3 Fig. 8"},
}


class ReportError(Exception):
    """An input problem; the message is the one line printed before exit status 2."""


# ---- the run: summary.json ----------------------------------------------------------------------

class RunInfo:
    """What the figures take from summary.json; every field None when the run has none (a failed run's
    summary may lack most of them)."""

    def __init__(self, scenario=None, description=None, step_s=None, metrics_after_s=None, status=None,
                 stopped_by=None, robot_metrics=None, mode=None):
        self.scenario = scenario
        self.description = description
        self.step_s = step_s                    # s
        self.metrics_after_s = metrics_after_s  # s: the evaluator's errors count from this time on
        self.status = status
        self.stopped_by = stopped_by            # e.g. "signal": a real-time run stopped early, cleanly
        self.robot_metrics = robot_metrics or {}  # {robot_id: metrics.robots.<id>}
        self.mode = mode                        # "lockstep" / "realtime" (run.mode)
        self.end_s = None                       # s since the start: the last time in the files


def read_summary(out_dir):
    """RunInfo of out_dir/summary.json (an empty one without the file); ReportError if it is malformed."""
    path = os.path.join(out_dir, "summary.json")
    if not os.path.exists(path):
        return RunInfo()
    try:
        with open(path) as f:
            summary = json.load(f)
    except (OSError, UnicodeDecodeError, ValueError) as e:
        raise ReportError("%s: not readable as JSON: %s" % (path, e))
    if not isinstance(summary, dict):
        raise ReportError("%s: not a JSON object" % path)

    def get(key, kind, positive=False):
        value = summary.get(key)
        if value is None:
            return None
        ok = isinstance(value, str) if kind is str else (isinstance(value, (int, float)) and not isinstance(value, bool)
                                                         and math.isfinite(value) and (value > 0 or not positive))
        if not ok:
            raise ReportError("%s: key '%s': %r is not a%s" % (path, key, value, " string" if kind is str else
                                                               (" positive number" if positive else " number")))
        return value

    robots = summary.get("metrics", {}).get("robots", {}) if isinstance(summary.get("metrics"), dict) else {}
    robot_metrics = {int(k): v for k, v in robots.items() if str(k).isdigit() and isinstance(v, dict)}
    run = summary.get("run") if isinstance(summary.get("run"), dict) else {}
    mode = run.get("mode") if isinstance(run.get("mode"), str) else None
    return RunInfo(get("scenario", str), get("description", str), get("step_s", float, positive=True),
                   get("metrics_after_s", float), get("status", str), get("stopped_by", str), robot_metrics, mode)


def run_start(data, step_s):
    """The run's start on the files' time axis (s): with the step length, the smallest t_s - step * step_s
    (0 in lockstep, where stamps are sim time; the wall clock at step 0 in real time); without it, the
    first time in the files."""
    starts = []
    for table in data.values():
        if "t_s" not in table or len(table["t_s"]) == 0:
            continue
        if step_s is not None and "header.step" in table:
            starts.append(float(np.min(table["t_s"] - table["header.step"] * step_s)))
        else:
            starts.append(float(np.min(table["t_s"])))
    return min(starts) if starts else 0.0


def shift_time(data, info):
    """Makes every t_s the time since the run's start, and sets info.end_s. Lockstep files, which start at
    0 already, are left as they are (their times are the steps' exact decimal times)."""
    start = run_start(data, info.step_s)
    if abs(start) > 1e-6:
        for table in data.values():
            if "t_s" in table:
                table["t_s"] = table["t_s"] - start
    ends = [float(np.max(table["t_s"])) for table in data.values() if "t_s" in table and len(table["t_s"])]
    info.end_s = max(ends) if ends else None


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


def read_table(path, columns, optional=()):
    """Reads a CSV file into {column: array} (floats; str arrays for TEXT_COLUMNS); checks the columns.
    The `optional` columns are read when the header has them."""
    name = os.path.basename(path)
    header = read_header(path)
    for column in columns:
        if column not in header:
            raise ReportError("%s: missing column '%s'" % (path, column))
    columns = list(columns) + [column for column in optional if column in header]
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


def read_file(path):
    """One known file: its table, None for a file no figure draws (header checked only); ReportError on bad
    input."""
    name = os.path.basename(path)
    if name in HEADER_ONLY:
        header = read_header(path)
        for column in SCHEMAS[name]:
            if column not in header:
                raise ReportError("%s: missing column '%s'" % (path, column))
        return None
    return read_table(path, SCHEMAS[name], OPTIONAL_COLUMNS.get(name, ()))


def load(out_dir):
    """Reads every known CSV file of out_dir that a figure draws: {file name: table}; checks the header of
    the others. Raises ReportError on bad input. (Parsing the files in worker processes cost more than it
    saved: pickling the tables back took longer than numpy's parser, measured in docs/performance.md.)"""
    if not os.path.isdir(out_dir):
        raise ReportError("%s: no such directory" % out_dir)
    csv_files = sorted(f for f in os.listdir(out_dir) if f.endswith(".csv"))
    if not csv_files:
        raise ReportError("%s: no CSV file (expected the output of `robodds run SCENARIO --out DIR`)" % out_dir)
    data = {}
    for name in csv_files:
        if name in SCHEMAS:
            table = read_file(os.path.join(out_dir, name))
            if table is not None:
                data[name] = table
    return data


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
    """Indices (i_truth, i_other) of the rows of two step-sorted tables with equal header.step (the first
    truth row of that step, as the evaluator's TruthWindow::at)."""
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


# ---- drawing helpers --------------------------------------------------------------------------

MAX_DRAWN_POINTS = 4000  # per line; long runs (100k rows per robot) are decimated for drawing only


def drawn(n):
    """Index slice that keeps at most MAX_DRAWN_POINTS of n rows, evenly spaced (paths, point clouds)."""
    return slice(None, None, max(1, -(-n // MAX_DRAWN_POINTS)))


def envelope(t, y, max_points=MAX_DRAWN_POINTS):
    """(t, y) of a time series thinned for drawing to at most max_points: each bucket of consecutive rows
    keeps its smallest and its largest value, in their order, so spikes stay visible; a bucket without a
    finite value keeps one NaN, so gaps stay gaps. Figures are never computed from the result."""
    n = len(t)
    if n <= max_points:
        return t, y
    size = -(-n // (max_points // 2))  # rows per bucket
    buckets = -(-n // size)
    pad = buckets * size - n
    tt = np.concatenate([t, np.full(pad, t[-1])]).reshape(buckets, size)
    yy = np.concatenate([y, np.full(pad, np.nan)]).reshape(buckets, size)
    finite = np.isfinite(yy)
    lo = np.argmin(np.where(finite, yy, np.inf), axis=1)
    hi = np.argmax(np.where(finite, yy, -np.inf), axis=1)
    first = np.minimum(lo, hi)
    second = np.maximum(lo, hi)
    rows = np.arange(buckets)
    t_out = np.column_stack([tt[rows, first], tt[rows, second]]).ravel()
    y_out = np.column_stack([yy[rows, first], yy[rows, second]]).ravel()
    empty = np.repeat(~finite.any(axis=1), 2)
    y_out[empty] = np.nan
    return t_out, y_out


def robot_colors(robots):
    cycle = matplotlib.rcParams["axes.prop_cycle"].by_key().get("color", ["C0"])
    return {robot: cycle[i % len(cycle)] for i, robot in enumerate(sorted(robots))}


def robot_label(robot, robots, what):
    """'robot 2 <what>', or '<what>' alone when the figure has one robot."""
    return what if len(robots) == 1 else "robot %d %s" % (robot, what)


def marker_color(colors):
    """The colour of a legend entry for a marker drawn in each robot's colour: that colour for one robot,
    black (the entry then explains the shape only) for several."""
    return next(iter(colors.values())) if len(colors) == 1 else "black"


class Layout:
    """Fixed margins in inches (fig.tight_layout() measured every tick label: about a third of the drawing
    time), and the figure's title lines above the top axes."""

    def __init__(self, left=0.85, right=0.25, bottom=0.6, top=0.35, hspace=0.25, wspace=0.25):
        self.left, self.right, self.bottom, self.top = left, right, bottom, top
        self.hspace, self.wspace = hspace, wspace


def new_figure(width, height):
    _load_matplotlib()
    fig = Figure(figsize=(width, height), dpi=DPI)
    FigureCanvasAgg(fig)
    return fig


def paper_figure(info, key):
    return PAPER_FIGURES.get(info.scenario or "", {}).get(key)


def subtitle(info, width_in):
    """The scenario line(s) under a title: name, description, and how the run ended when not normally."""
    parts = []
    if info.scenario:
        parts.append("scenario %s%s%s" % (info.scenario, " (real time)" if info.mode == "realtime" else "",
                                          ": %s" % info.description if info.description else ""))
    if info.stopped_by:
        parts.append("stopped by %s%s" % (info.stopped_by, " at t = %.1f s" % info.end_s if info.end_s is not None
                                          else ""))
    elif info.status and info.status != "completed":
        parts.append("run %s%s" % (info.status, " at t = %.1f s" % info.end_s if info.end_s is not None else ""))
    if not parts:
        return []
    return textwrap.wrap("; ".join(parts), width=max(40, int(width_in * 15)))[:3]


def headline(fig, info, what, key, layout):
    """Titles fig: '<what> (paper N Fig. M)' where the scenario is that figure, then the scenario's lines,
    and places the axes inside the layout's margins (the top margin grows with the title lines)."""
    width, height = fig.get_size_inches()
    paper = paper_figure(info, key)
    title = what + (" (%s)" % paper if paper else "")
    lines = subtitle(info, width)
    fig.suptitle(title, x=0.5, y=1.0 - 0.1 / height, va="top", fontsize=11)
    if lines:
        fig.text(0.5, 1.0 - 0.38 / height, "\n".join(lines), ha="center", va="top", fontsize=8, color="0.3")
    top = layout.top + 0.35 + 0.15 * len(lines)
    fig.subplots_adjust(left=layout.left / width, right=1.0 - layout.right / width, bottom=layout.bottom / height,
                        top=1.0 - top / height, hspace=layout.hspace, wspace=layout.wspace)
    return title


def note_empty(ax, text):
    """A panel with nothing to draw says why, in its middle."""
    ax.text(0.5, 0.5, text, transform=ax.transAxes, ha="center", va="center", color="0.35", fontsize=8,
            wrap=True)


def world_axes(ax, handles):
    """Legend, equal axes in world metres and grid of an x-y plot."""
    ax.legend(handles=handles, loc="best", fontsize=8, framealpha=0.85)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, alpha=0.3)


# ---- paper 1 (and any robot): paths, commands, distances, errors ---------------------------------

def fig_trajectory(data, missions, info):
    truth = by_robot(data.get("plant_state.csv"))
    estimate = {r: valid_rows(t) for r, t in by_robot(data.get("estimate_pose.csv")).items()}
    robots = sorted(set(truth) | set(estimate))
    if not robots:
        return None
    everyone = sorted(set(robots) | set(missions))
    colors = robot_colors(everyone)
    fig = new_figure(7.5, 7.3)
    ax = fig.subplots()
    handles = []
    for robot in everyone:
        c = colors[robot]
        if robot in truth and len(truth[robot]["x"]):
            t = truth[robot]
            d = drawn(len(t["x"]))
            ax.plot(t["x"][d], t["y"][d], "-", color=c, lw=1.6)
            handles.append(Line2D([], [], color=c, ls="-", lw=1.6, label=robot_label(robot, everyone, "true path")))
        if robot in estimate and len(estimate[robot]["x"]):
            e = estimate[robot]
            d = drawn(len(e["x"]))
            ax.plot(e["x"][d], e["y"][d], "--", color=c, lw=1.2)
            handles.append(Line2D([], [], color=c, ls="--", lw=1.2,
                                  label=robot_label(robot, everyone, "estimate (valid samples)")))
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
    marker = marker_color(colors)
    if missions:
        handles.append(Line2D([], [], color=marker, ls="none", marker="^", mfc="none", mew=1.5, ms=9,
                              label="way-point (numbered in order)"))
    handles.append(Line2D([], [], color=marker, ls="none", marker="o", mfc=marker, mec="black", ms=8, label="start"))
    world_axes(ax, handles)
    headline(fig, info, "Trajectory", "trajectory", Layout(top=0.1))
    return fig


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


def fig_velocity(data, info):
    cmds = by_robot(data.get("plant_cmd.csv"))
    if not cmds:
        return None
    states = by_robot(data.get("plant_state.csv"))
    colors = robot_colors(cmds)
    fig = new_figure(8.0, 6.2)
    ax_v, ax_w = fig.subplots(2, 1, sharex=True)
    for robot, cmd in cmds.items():
        v, omega = command_twist(cmd, states.get(robot))
        label = "robot %d" % robot
        ax_v.plot(*envelope(cmd["t_s"], v), color=colors[robot], lw=1.3, drawstyle="steps-post", label=label)
        ax_w.plot(*envelope(cmd["t_s"], omega), color=colors[robot], lw=1.3, drawstyle="steps-post", label=label)
    ax_v.set_ylabel("v [m/s]")
    ax_w.set_ylabel("\u03c9 [rad/s]")  # plain text: no mathtext parser (~30 ms the first time)
    ax_w.set_xlabel("time [s]")
    for ax in (ax_v, ax_w):
        ax.grid(True, alpha=0.3)
        ax.axhline(0.0, color="black", lw=0.6)
    ax_v.legend(loc="best", fontsize=8)
    headline(fig, info, "Commanded velocities", "velocity", Layout(top=0.1, hspace=0.12))
    return fig


def distances_with_gaps(status):
    """(distance to the way-point, to the final one, mask of rows without one): NaN where the controller
    computed no distance (a state other than TRACKING/DONE: no valid estimate, no mission) and control/status
    carries 0. Runs recorded before control/status had `state` keep every row."""
    if "state" not in status:
        return status["distance_to_waypoint"], status["distance_to_final"], np.zeros(len(status["t_s"]), dtype=bool)
    missing = (status["state"] != STATE_TRACKING) & (status["state"] != STATE_DONE)
    return (np.where(missing, np.nan, status["distance_to_waypoint"]), np.where(missing, np.nan, status["distance_to_final"]),
            missing)


def fig_distance(data, info):
    status = by_robot(data.get("control_status.csv"))
    if not status:
        return None
    colors = robot_colors(status)
    fig = new_figure(8.0, 6.2)
    ax_wp, ax_final = fig.subplots(2, 1, sharex=True)
    any_reached = any_missing = False
    for robot, s in status.items():
        c = colors[robot]
        to_waypoint, to_final, missing = distances_with_gaps(s)
        ax_wp.plot(*envelope(s["t_s"], to_waypoint), color=c, lw=1.3)
        ax_final.plot(*envelope(s["t_s"], to_final), color=c, lw=1.3)
        if np.any(missing):
            any_missing = True
            for ax in (ax_wp, ax_final):  # one artist per axes, however many intervals
                ax.fill_between(s["t_s"], 0.0, 1.0, where=missing, step="post", color="0.85", lw=0,
                                transform=ax.get_xaxis_transform(), zorder=0)
        # Mark each way-point reached (waypoints_reached goes up) on the upper plot.
        up = np.flatnonzero(np.diff(s["waypoints_reached"]) > 0) + 1
        if len(up):
            ax_wp.plot(s["t_s"][up], to_waypoint[up - 1], "v", color=c, ms=6, ls="none")
            any_reached = True
    ax_wp.set_ylabel("to current way-point [m]")
    ax_final.set_ylabel("to final way-point [m]")
    ax_final.set_xlabel("time [s]")
    for ax in (ax_wp, ax_final):
        ax.grid(True, alpha=0.3)
        ax.set_ylim(bottom=0.0)
    handles = [Line2D([], [], color=colors[r], lw=1.3, label="robot %d" % r) for r in sorted(status)]
    if any_reached:
        handles.append(Line2D([], [], color=marker_color(colors), ls="none", marker="v", ms=6, label="way-point reached"))
    if any_missing:
        handles.append(Patch(color="0.85", label="no valid estimate: no distance"))
    ax_wp.legend(handles=handles, loc="best", fontsize=8)
    headline(fig, info, "Distance to the way-points, from the controller's estimate", "distance",
             Layout(top=0.1, hspace=0.12))
    return fig


def metrics_from_step(info):
    """The first step the evaluator's errors count (MetricsSetup::metrics_from_step: llround(after / step))
    and the time it stands for; (None, 0.0) when summary.json does not say."""
    if info.metrics_after_s is None:
        return None, 0.0
    if info.step_s is None:
        return None, float(info.metrics_after_s)
    return int(math.floor(info.metrics_after_s / info.step_s + 0.5)), float(info.metrics_after_s)


def position_rmse(truth, rows, from_step, from_s):
    """2-D position RMSE (m) and sample count as summary.json's pf_rmse_m / measurement_rmse_m (the waypoints
    metrics module): every row at a step >= from_step (time >= from_s without steps) - an estimate valid or
    not - matched with the truth row of the same step, sqrt(mean(dx^2 + dy^2)); (nan, 0) without a match."""
    i_truth, i_rows = match_steps(truth, rows)
    if from_step is not None:
        keep = rows["header.step"][i_rows] >= from_step
    else:
        keep = rows["t_s"][i_rows] >= from_s - 1e-9
    i_truth, i_rows = i_truth[keep], i_rows[keep]
    if not len(i_rows):
        return float("nan"), 0
    dx = rows["x"][i_rows] - truth["x"][i_truth]
    dy = rows["y"][i_rows] - truth["y"][i_truth]
    return float(np.sqrt(np.mean(dx * dx + dy * dy))), len(i_rows)


def error_rmses(data, info):
    """{(robot, 'measurement'|'estimate'): (rmse m, count)} of the robots with truth; warns on stderr when one
    differs from summary.json's (a definition that drifted apart)."""
    truth = by_robot(data.get("plant_state.csv"))
    from_step, from_s = metrics_from_step(info)
    rmses = {}
    for source, name, key in (("measurement", "sensor_position.csv", "measurement_rmse_m"),
                              ("estimate", "estimate_pose.csv", "pf_rmse_m")):
        for robot, rows in by_robot(data.get(name)).items():
            if robot not in truth:
                continue
            value, count = position_rmse(truth[robot], rows, from_step, from_s)
            rmses[(robot, source)] = (value, count)
            expected = info.robot_metrics.get(robot, {}).get(key)
            if (isinstance(expected, (int, float)) and count and info.metrics_after_s is not None
                    and abs(value - expected) > 1e-6 * max(1.0, abs(expected))):
                sys.stderr.write("report: robot %d's %s RMSE %.6g m differs from summary.json's %s %.6g m\n"
                                 % (robot, source, value, key, expected))
    return rmses


def fig_errors(data, info, rmses):
    """pf_error.png (estimate and raw fixes vs truth) or, without estimate_pose.csv, measurement_error.png."""
    truth = by_robot(data.get("plant_state.csv"))
    has_estimate = "estimate_pose.csv" in data
    estimates = by_robot(data.get("estimate_pose.csv"))
    fixes = by_robot(data.get("sensor_position.csv"))
    colors = robot_colors(set(truth) | set(estimates) | set(fixes))
    fig = new_figure(8.0, 7.0)
    axes = fig.subplots(2, 1, sharex=True)
    everyone = sorted(colors)
    for robot in everyone:
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
            value, _ = rmses.get((robot, source), (float("nan"), 0))
            rmse = "2-D RMSE %.3g m" % value
            for k, (ax, axis) in enumerate(zip(axes, ("x", "y"))):
                err = rows[axis][i_rows] - truth[robot][axis][i_truth]
                if source == "measurement":  # one robot: grey fixes, so its estimate's line stands out
                    d = drawn(len(t))
                    label = robot_label(robot, everyone, "raw fix (%s)" % rmse) if k == 0 else None
                    ax.plot(t[d], err[d], ".", color=c if len(everyone) > 1 else "0.55", ms=3.5, alpha=0.45,
                            label=label)
                    continue
                valid = rows["valid"][i_rows] != 0
                label = robot_label(robot, everyone, "estimate (%s)" % rmse) if k == 0 else None
                ax.plot(*envelope(t, np.where(valid, err, np.nan)), "-", color=c, lw=1.5, label=label)
                if not np.all(valid):
                    label = robot_label(robot, everyone, "estimate, not valid (counted too)") if k == 0 else None
                    ax.plot(*envelope(t, np.where(valid, np.nan, err)), ":", color=c, lw=1.0, label=label)
    for ax, axis in zip(axes, ("x", "y")):
        ax.set_ylabel("%s error [m]" % axis)
        ax.axhline(0.0, color="black", lw=0.6)
        ax.grid(True, alpha=0.3)
    if axes[0].get_legend_handles_labels()[0]:
        axes[0].legend(loc="upper right", fontsize=7, framealpha=0.85)
    axes[1].set_xlabel("time [s]")
    note = textwrap.wrap(rmse_definition(info, has_estimate), width=int(fig.get_size_inches()[0] * 17))
    fig.text(0.01, 0.01, "\n".join(note), fontsize=7, color="0.3", va="bottom")
    layout = Layout(top=0.1, bottom=0.55 + 0.13 * len(note), hspace=0.12)
    if has_estimate:
        headline(fig, info, "Position error of the estimate and of the raw fixes vs truth", "pf_error", layout)
    else:
        headline(fig, info, "Raw position fix error vs truth", "measurement_error", layout)
    return fig


def rmse_definition(info, has_estimate):
    """The footnote of the error figure: how its RMSEs are computed, the same as summary.json's."""
    _, from_s = metrics_from_step(info)
    return ("2-D RMSE = sqrt(mean(dx\u00b2 + dy\u00b2)) over every sample from t = %g s%s, "
            "matched with the truth at its step: summary.json's %s%s"
            % (from_s, " (an estimate valid or not)" if has_estimate else "",
               "pf_rmse_m and measurement_rmse_m" if has_estimate else "measurement_rmse_m",
               "" if info.metrics_after_s is not None else " (summary.json gives no metrics_after_s: from t = 0 here)"))


def error_figure_name(data):
    """pf_error.png / measurement_error.png / None (the errors need truth and fixes or estimates)."""
    if "plant_state.csv" not in data or not by_robot(data.get("plant_state.csv")):
        return None
    if "estimate_pose.csv" in data:
        return "pf_error.png"
    return "measurement_error.png" if "sensor_position.csv" in data else None


# ---- paper 2: circumnavigation with range-rate observers ---------------------------------------

ZOOM_WINDOW_S = 60.0
MAX_ZOOM_WINDOWS = 4

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




def departures(schedules):
    """{robot: time (s) its assignment went inactive after an active one}: it left the team (LEAVE)."""
    left = {}
    for robot, rows in schedules.items():
        was_active = False
        for t, active in zip(rows["t_s"], rows["active"]):
            if active != 0:
                was_active = True
                left.pop(robot, None)
            elif was_active and robot not in left:
                left[robot] = float(t)
    return left


def empty_window_reason(robot, start, end, schedules, left):
    """Why a zoom panel of `robot` over [start, end) has nothing to draw."""
    if robot in left and left[robot] <= start + 1e-9:
        return "robot %d left at t = %g s:\nno target, no range rate" % (robot, left[robot])
    rows = schedules.get(robot)
    if rows is None or not np.any((rows["active"] != 0) & (rows["t_s"] < end)):
        return "robot %d: no target assigned\nby t = %g s" % (robot, end)
    return "robot %d: no valid observer\noutput in %g-%g s" % (robot, start, end)


def fig_p2_trajectories(truths, schedules, info):
    if not truths:
        return None
    colors = robot_colors(truths)
    fig = new_figure(7.5, 7.3)
    ax = fig.subplots()
    for robot, tr in truths.items():
        c = colors[robot]
        d = drawn(len(tr["x"]))
        ax.plot(tr["x"][d], tr["y"][d], "-", color=c, lw=1.2)
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
    marker = marker_color(colors)
    handles = [Line2D([], [], color=colors[r], lw=1.2, label="robot %d" % r) for r in sorted(colors)]
    handles += [Line2D([], [], color=marker, ls="none", marker="o", mfc=marker, mec="black", ms=7, label="start"),
                Line2D([], [], color=marker, ls="none", marker="s", mfc=marker, mec="black", ms=6, label="end")]
    if targets:
        handles.append(Line2D([], [], color="black", ls=":", lw=1.0, marker="x", mew=2, label="target, desired radius"))
    world_axes(ax, handles)
    headline(fig, info, "Trajectories around the targets", "p2_trajectories", Layout(top=0.1))
    return fig


def fig_p2_range_rate(data, truths, schedules, info):
    estimates = by_robot(data.get("observer_range_rate.csv"))
    if not estimates:
        return None
    robots = sorted(set(estimates) | set(truths))
    colors = robot_colors(robots)
    left = departures(schedules)
    fig = new_figure(9.0, 2.2 * len(robots) + 1.2)
    axes = fig.subplots(len(robots), 1, sharex=True, squeeze=False)
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
        if robot in left:
            ax.axvline(left[robot], color="black", ls="--", lw=1.0, label="left the team (t = %g s)" % left[robot])
        ax.set_ylabel("robot %d\nrange rate [m/s]" % robot, fontsize=8)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right", fontsize=7, framealpha=0.85)
    axes[-1, 0].set_xlabel("time [s]")
    headline(fig, info, "True and observed range rate", "p2_range_rate", Layout(top=0.1, hspace=0.12))
    return fig


def fig_p2_observer_zoom(data, truths, schedules, info):
    sta = by_robot(data.get("observer_range_rate.csv"))
    linear = by_robot(data.get("observer_range_rate_linear.csv"))
    if not sta and not linear:
        return None
    starts = assignment_starts(schedules) or [0.0]
    robots = sorted(set(sta) | set(linear))
    left = departures(schedules)
    fig = new_figure(4.5 * len(starts) + 1.0, 2.2 * len(robots) + 1.4)
    axes = fig.subplots(len(robots), len(starts), squeeze=False)
    empty = {}
    for i, robot in enumerate(robots):
        for j, start in enumerate(starts):
            ax = axes[i, j]
            end = start + ZOOM_WINDOW_S
            lines = 0  # series with a line to show (two finite points at least)
            if robot in truths:
                tr = truths[robot]
                keep = (tr["t_s"] >= start) & (tr["t_s"] < end) & np.isfinite(tr["range_rate"])
                lines += int(np.sum(keep)) >= 2
                d = drawn(int(np.sum(keep)))
                ax.plot(tr["t_s"][keep][d], tr["range_rate"][keep][d], "-", color="black", lw=1.2, label="true")
            for rows_by_robot, color, label in ((sta, "C0", "super-twisting"), (linear, "C1", "linear")):
                if robot not in rows_by_robot:
                    continue
                t, rate, _ = masked_estimate(rows_by_robot[robot])
                keep = (t >= start) & (t < end)
                lines += int(np.sum(keep & np.isfinite(rate))) >= 2
                d = drawn(int(np.sum(keep)))
                ax.plot(t[keep][d], rate[keep][d], "-", color=color, lw=1.0, label=label)
            if not lines:  # robot 4 after it left: one sample of each observer at the switch, no truth
                for line in list(ax.lines):
                    line.remove()
                note_empty(ax, empty_window_reason(robot, start, end, schedules, left))
                empty[(i, j)] = True
            ax.set_xlim(start, end)
            ax.grid(True, alpha=0.3)
            if j == 0:
                ax.set_ylabel("robot %d\nrange rate [m/s]" % robot, fontsize=8)
            if i == 0:
                ax.set_title("%g-%g s" % (start, end), fontsize=9)
            if i == len(robots) - 1:
                ax.set_xlabel("time [s]")
    # An empty panel takes the range rate scale of its robot's other panels (else the figure's), so its
    # axis means what its neighbours' do.
    drawn_limits = {(i, j): axes[i, j].get_ylim() for i in range(len(robots)) for j in range(len(starts))
                    if (i, j) not in empty}
    for (i, j) in empty:
        row = [lim for (r, _), lim in drawn_limits.items() if r == i] or list(drawn_limits.values())
        if row:
            axes[i, j].set_ylim(min(lo for lo, _ in row), max(hi for _, hi in row))
    for (i, j), ax in np.ndenumerate(axes):
        if (i, j) not in empty:
            ax.legend(loc="best", fontsize=7, framealpha=0.85)
            break
    headline(fig, info, "True vs super-twisting vs linear range rate after each assignment", "p2_observer_zoom",
             Layout(top=0.35, hspace=0.3, wspace=0.3))
    return fig


def fig_p2_formation(truths, info):
    if not truths:
        return None
    spacing = spacing_errors(truths)
    colors = robot_colors(truths)
    fig = new_figure(9.0, 6.2)
    ax_r, ax_s = fig.subplots(2, 1, sharex=True)
    for robot, tr in truths.items():
        d = drawn(len(tr["t_s"]))
        ax_r.plot(tr["t_s"][d], (tr["range"] - tr["desired_radius"])[d], color=colors[robot], lw=1.0,
                  label="robot %d" % robot)
        ax_s.plot(tr["t_s"][d], np.degrees(spacing[robot])[d], color=colors[robot], lw=1.0, label="robot %d" % robot)
    ax_r.set_ylabel("radius error [m]")
    ax_s.set_ylabel("spacing error [deg]\n(gap to next - 360/n)")
    ax_s.set_xlabel("time [s]")
    for ax in (ax_r, ax_s):
        ax.grid(True, alpha=0.3)
        ax.axhline(0.0, color="black", lw=0.6)
        ax.legend(loc="upper right", fontsize=7)
        ax.set_yscale("symlog", linthresh=1.0)
    headline(fig, info, "Formation: distance to the target minus the desired radius, angular spacing",
             "p2_formation", Layout(top=0.1, hspace=0.12))
    return fig


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




def p3_pairs(stages):
    return sorted(set(pair for _, by in stages for pair in by))


def fig_p3_trajectory(stages, pair, info):
    robot, peer = pair
    fig = new_figure(7.0, 6.8)
    ax = fig.subplots()
    # The truth of the stage file with the most of it (every file carries it for its own rows).
    truths = [by[pair] for _, by in stages if pair in by]
    truth = max(truths, key=lambda rows: int(np.sum(np.isfinite(rows["true_x"]))))
    handles = []
    for stage, by in stages:
        rows = by.get(pair)
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
    world_axes(ax, handles)
    headline(fig, info, "Robot %d in robot %d's frame: true and estimated" % (peer, robot), "p3_relative_trajectory",
             Layout(top=0.1))
    return fig


def fig_p3_errors(stages, info):
    pairs = p3_pairs(stages)
    if not pairs:
        return None
    fig = new_figure(5.0 * len(pairs) + 1.5, 6.4)
    axes = fig.subplots(2, len(pairs), sharex=True, squeeze=False)
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
    headline(fig, info, "Relative pose error per stage", "p3_relative_error", Layout(top=0.35, hspace=0.12))
    return fig


# ---- the run's figures ----------------------------------------------------------------------------

def figure_jobs(data, missions, info):
    """[(file name, build)] of the figures this run's files allow, in drawing order; build() returns the
    Figure (None: nothing to draw). Input-dependent figures (RMSEs, paper 2 truths) are computed here, in
    the calling process, before any figure."""
    jobs = [("trajectory.png", lambda: fig_trajectory(data, missions, info)),
            ("velocity.png", lambda: fig_velocity(data, info)),
            ("distance.png", lambda: fig_distance(data, info))]
    errors = error_figure_name(data)
    if errors:
        rmses = error_rmses(data, info)
        jobs.append((errors, lambda: fig_errors(data, info, rmses)))
    truths, schedules = paper2_truths(data)
    jobs += [("p2_trajectories.png", lambda: fig_p2_trajectories(truths, schedules, info)),
             ("p2_range_rate.png", lambda: fig_p2_range_rate(data, truths, schedules, info)),
             ("p2_observer_zoom.png", lambda: fig_p2_observer_zoom(data, truths, schedules, info)),
             ("p2_formation.png", lambda: fig_p2_formation(truths, info))]
    stages = paper3_stages(data)
    for pair in p3_pairs(stages):
        jobs.append(("p3_relative_trajectory_%d_%d.png" % pair,
                     lambda pair=pair: fig_p3_trajectory(stages, pair, info)))
    jobs.append(("p3_relative_error.png", lambda: fig_p3_errors(stages, info)))
    return jobs


_JOBS = []      # the jobs of the report being drawn, inherited by the forked workers
_OUT_DIR = ""


def _draw(index):
    """Builds and saves job `index`: its path, or None if it had nothing to draw."""
    name, build = _JOBS[index]
    fig = build()
    if fig is None:
        return None
    path = os.path.join(_OUT_DIR, name)
    # zlib level 3: 25 ms less per figure than PIL's default 6, the file as small (pf_error.png of
    # paper1_waypoints: 228.8 against 230.1 kB)
    fig.savefig(path, dpi=DPI, pil_kwargs={"compress_level": PNG_COMPRESS_LEVEL})
    return path


def worker_count(jobs):
    """ROBODDS_REPORT_JOBS, else one per idle processor (those this process may run on minus the 1-minute
    load average), at most one per figure. On a busy machine the workers cost more than they saved (beside
    eight CPU hogs on 2 cores: wall x1.16, CPU x1.11 against drawing in this process; docs/performance.md)."""
    wanted = os.environ.get("ROBODDS_REPORT_JOBS", "").strip()
    if wanted:
        if not wanted.isdigit() or int(wanted) < 1:
            raise ReportError("ROBODDS_REPORT_JOBS: '%s' is not a whole number >= 1" % wanted)
        count = int(wanted)
    else:
        processors = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
        count = processors - int(round(os.getloadavg()[0]))
    return max(1, min(count, jobs))


def draw_all(jobs, out_dir):
    """Draws the jobs, in forked worker processes when processors are idle (worker_count(); each figure is
    independent; matplotlib and the data are already in memory, inherited at the fork); the written paths
    in job order."""
    global _JOBS, _OUT_DIR
    _JOBS, _OUT_DIR = jobs, out_dir
    workers = worker_count(len(jobs))
    try:
        if workers > 1:
            import multiprocessing

            with multiprocessing.get_context("fork").Pool(workers) as pool:
                paths = pool.map(_draw, range(len(jobs)), chunksize=1)
        else:
            paths = [_draw(i) for i in range(len(jobs))]
    finally:
        _JOBS, _OUT_DIR = [], ""
    return [path for path in paths if path]


def prepare(out_dir):
    """(data, missions, info) of out_dir, every input checked, times from the run's start. Raises
    ReportError on bad input."""
    data = load(out_dir)
    info = read_summary(out_dir)
    missions = waypoints_by_robot(data.get("mission_waypoints.csv"), os.path.join(out_dir, "mission_waypoints.csv"))
    shift_time(data, info)
    return data, missions, info


def report(out_dir):
    """Writes the figures of out_dir; returns the written paths. Raises ReportError on bad input."""
    # Every input check happens before the first figure, so bad input leaves no figure behind.
    data, missions, info = prepare(out_dir)
    if not data:
        return []
    jobs = figure_jobs(data, missions, info)
    worker_count(len(jobs))  # a bad ROBODDS_REPORT_JOBS, before any figure
    _load_matplotlib()
    written = draw_all(jobs, out_dir)
    for path in written:
        print(path)
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
