"""Unit tests of report.py on synthetic robodds outputs (python3 -m unittest -v test_report).

Writes only into temporary directories: the runs, the figures and matplotlib's config/cache dir.
"""

import atexit
import contextlib
import csv
import io
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPORT = os.path.join(HERE, "report.py")

# Keep matplotlib's font cache and the bytecode of report.py out of the home and source directories.
_MPL_DIR = tempfile.mkdtemp(prefix="robodds-report-mpl-")
atexit.register(shutil.rmtree, _MPL_DIR, True)
os.environ["MPLCONFIGDIR"] = _MPL_DIR
os.environ.setdefault("MPLBACKEND", "Agg")
sys.dont_write_bytecode = True
sys.path.insert(0, HERE)
import report  # noqa: E402

HEADER = ["t_s", "robot_id", "header.step", "header.next_step", "header.stamp_ns"]
COLUMNS = {
    "plant_state.csv": HEADER + ["x", "y", "theta", "v", "omega"],
    "plant_cmd.csv": HEADER + ["mode", "v", "omega", "v_left", "v_right"],
    "sensor_position.csv": HEADER + ["x", "y", "var_x", "var_y"],
    "sensor_odometry.csv": HEADER + ["v", "omega", "dt_s", "var_v", "var_omega"],
    "estimate_pose.csv": HEADER + ["x", "y", "theta"] + ["cov[%d]" % i for i in range(9)] + ["valid"],
    "control_status.csv": HEADER + ["waypoint_index", "waypoints_total", "waypoints_reached",
                                    "distance_to_waypoint", "distance_to_final", "alpha", "sigma", "done"],
    "mission_waypoints.csv": HEADER + ["waypoints"],
}
SMOKE_FILES = ["plant_state.csv", "plant_cmd.csv", "sensor_position.csv"]
ALL_FIGURES = ["trajectory.png", "velocity.png", "distance.png", "pf_error.png"]
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def synthetic_rows(step_s=0.05, duration_s=30.0, seed=7):
    """Two robots driving to their way-points with a simple heading controller; rows per file name."""
    rng = random.Random(seed)
    missions = {1: [(4.0, 0.0), (4.0, 4.0), (0.0, 4.0)], 2: [(-3.0, 2.0), (-6.0, -1.0)]}
    poses = {1: [0.0, 0.0, 0.0], 2: [0.0, 0.0, math.pi / 2]}
    target = {1: 0, 2: 0}
    rows = {name: [] for name in COLUMNS}
    for robot, wps in missions.items():
        rows["mission_waypoints.csv"].append([0.0, robot, 0, 0, 0, ";".join("%g:%g" % p for p in wps)])
    est_err = {1: [0.0, 0.0], 2: [0.0, 0.0]}
    for step in range(int(duration_s / step_s) + 1):
        t = step * step_s
        head = lambda robot, nxt: [round(t, 9), robot, step, step + nxt, int(t * 1e9)]  # noqa: E731
        for robot, wps in missions.items():
            x, y, th = poses[robot]
            k = target[robot]
            gx, gy = wps[k]
            dist = math.hypot(gx - x, gy - y)
            if dist < 0.3 and k + 1 < len(wps):
                target[robot] = k = k + 1
                gx, gy = wps[k]
                dist = math.hypot(gx - x, gy - y)
            done = k == len(wps) - 1 and dist < 0.3
            alpha = math.atan2(gy - y, gx - x) - th
            alpha = math.atan2(math.sin(alpha), math.cos(alpha))
            v = 0.0 if done else min(1.0, dist) * max(0.0, math.cos(alpha))
            omega = 0.0 if done else max(-1.5, min(1.5, 2.0 * alpha))
            final = math.hypot(wps[-1][0] - x, wps[-1][1] - y)
            rows["plant_state.csv"].append(head(robot, 1) + [x, y, th, v, omega])
            if step % 2 == 0:
                rows["plant_cmd.csv"].append(head(robot, 2) + [0, v, omega, 0, 0])
                rows["sensor_odometry.csv"].append(head(robot, 2) + [v, omega, 2 * step_s, 0.01, 0.01])
                rows["control_status.csv"].append(
                    head(robot, 2) + [k, len(wps), k + (1 if done else 0), dist, final, alpha, 0.0, int(done)])
            if step % 2 == 0:
                rows["sensor_position.csv"].append(
                    head(robot, 2) + [x + rng.gauss(0, 1.5), y + rng.gauss(0, 1.5), 2.25, 2.25])
                e = est_err[robot]
                e[0] = 0.9 * e[0] + rng.gauss(0, 0.08)
                e[1] = 0.9 * e[1] + rng.gauss(0, 0.08)
                cov = [0.04, 0, 0, 0, 0.04, 0, 0, 0, 0.01]
                rows["estimate_pose.csv"].append(
                    head(robot, 2) + [x + e[0], y + e[1], th] + cov + [0 if step == 0 else 1])
            poses[robot] = [x + v * math.cos(th) * step_s, y + v * math.sin(th) * step_s, th + omega * step_s]
    return rows


def write_run(out_dir, files=None, rows=None):
    """Writes the synthetic CSV files (all of them, or the names in files) into out_dir."""
    rows = rows or synthetic_rows()
    for name in files or COLUMNS:
        with open(os.path.join(out_dir, name), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(COLUMNS[name])
            w.writerows(rows[name])
    return rows


def run_main(out_dir):
    """report.main in-process: (exit status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = report.main([out_dir])
    return status, out.getvalue(), err.getvalue()


class ReportTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.rows = synthetic_rows()

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="robodds-report-test-")
        self.addCleanup(shutil.rmtree, self.dir, True)

    def pngs(self):
        return sorted(f for f in os.listdir(self.dir) if f.endswith(".png"))

    def assert_png(self, name):
        path = os.path.join(self.dir, name)
        self.assertTrue(os.path.isfile(path), name)
        self.assertGreater(os.path.getsize(path), 1000, name)
        with open(path, "rb") as f:
            self.assertEqual(f.read(8), PNG_MAGIC, name)

    def test_full_run_writes_every_figure(self):
        write_run(self.dir, rows=self.rows)
        status, out, err = run_main(self.dir)
        self.assertEqual(status, 0, err)
        self.assertEqual(self.pngs(), sorted(ALL_FIGURES))
        for name in ALL_FIGURES:
            self.assert_png(name)
        # One line per written file, naming it.
        self.assertEqual(sorted(out.splitlines()), sorted(os.path.join(self.dir, f) for f in ALL_FIGURES))

    def test_smoke_run_via_cli(self):
        # The platform smoke scenario records only these three topics.
        write_run(self.dir, files=SMOKE_FILES, rows=self.rows)
        proc = subprocess.run([sys.executable, REPORT, self.dir], capture_output=True, text=True, timeout=60)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        expected = ["measurement_error.png", "trajectory.png", "velocity.png"]
        self.assertEqual(self.pngs(), expected)
        for name in expected:
            self.assert_png(name)
        self.assertEqual(sorted(proc.stdout.splitlines()), [os.path.join(self.dir, f) for f in expected])

    def test_missing_inputs_skip_figures(self):
        write_run(self.dir, files=["control_status.csv", "sensor_odometry.csv"], rows=self.rows)
        status, out, err = run_main(self.dir)
        self.assertEqual(status, 0, err)
        self.assertEqual(self.pngs(), ["distance.png"])

    def test_missing_directory_exits_2(self):
        missing = os.path.join(self.dir, "no-such-run")
        proc = subprocess.run([sys.executable, REPORT, missing], capture_output=True, text=True, timeout=60)
        self.assertEqual(proc.returncode, 2)
        self.assertEqual(len(proc.stderr.strip().splitlines()), 1, proc.stderr)
        self.assertIn(missing, proc.stderr)
        self.assertEqual(proc.stdout, "")

    def test_directory_without_csv_exits_2(self):
        with open(os.path.join(self.dir, "summary.json"), "w") as f:
            f.write("{}\n")
        status, out, err = run_main(self.dir)
        self.assertEqual(status, 2)
        self.assertIn("no CSV", err)
        self.assertIn(self.dir, err)

    def test_missing_column_names_file_and_column(self):
        write_run(self.dir, rows=self.rows)
        path = os.path.join(self.dir, "estimate_pose.csv")
        with open(path) as f:
            lines = f.read().splitlines()
        lines[0] = lines[0].replace(",theta,", ",heading,")
        with open(path, "w") as f:
            f.write("\n".join(lines) + "\n")
        status, out, err = run_main(self.dir)
        self.assertEqual(status, 2)
        self.assertEqual(len(err.strip().splitlines()), 1, err)
        self.assertIn("estimate_pose.csv", err)
        self.assertIn("'theta'", err)
        self.assertEqual(self.pngs(), [])  # checked before any figure is drawn

    def test_empty_csv_and_bad_values_are_malformed(self):
        open(os.path.join(self.dir, "plant_cmd.csv"), "w").close()
        status, _, err = run_main(self.dir)
        self.assertEqual(status, 2)
        self.assertIn("plant_cmd.csv", err)

        with open(os.path.join(self.dir, "plant_cmd.csv"), "w") as f:
            f.write(",".join(COLUMNS["plant_cmd.csv"]) + "\n0.0,1,0,2,0,0,fast,0.1,0,0\n")
        status, _, err = run_main(self.dir)
        self.assertEqual(status, 2)
        self.assertIn("plant_cmd.csv: line 2, column 'v'", err)

        with open(os.path.join(self.dir, "plant_cmd.csv"), "w") as f:
            f.write(",".join(COLUMNS["plant_cmd.csv"]) + "\n0.0,1,0,2,0,0,1.0\n")
        status, _, err = run_main(self.dir)
        self.assertEqual(status, 2)
        self.assertIn("line 2 has 7 fields", err)

    def test_bad_waypoint_list_is_malformed(self):
        with open(os.path.join(self.dir, "mission_waypoints.csv"), "w") as f:
            f.write(",".join(COLUMNS["mission_waypoints.csv"]) + "\n0.0,1,0,0,0,1:2;3\n")
        status, _, err = run_main(self.dir)
        self.assertEqual(status, 2)
        self.assertIn("mission_waypoints.csv: column 'waypoints'", err)
        self.assertEqual(self.pngs(), [])


class HelperTest(unittest.TestCase):
    def test_parse_waypoints(self):
        wp = report.parse_waypoints("1:2;-3.5:4e1;")
        self.assertEqual(wp.tolist(), [[1.0, 2.0], [-3.5, 40.0]])
        self.assertEqual(report.parse_waypoints("").shape, (0, 2))

    def test_by_robot_groups_interleaved_rows_in_step_order(self):
        import numpy as np
        table = {"robot_id": np.array([2.0, 1.0, 2.0, 1.0]), "header.step": np.array([5.0, 3.0, 1.0, 7.0]),
                 "x": np.array([20.0, 10.0, 21.0, 11.0])}
        groups = report.by_robot(table)
        self.assertEqual(sorted(groups), [1, 2])
        self.assertEqual(groups[1]["x"].tolist(), [10.0, 11.0])
        self.assertEqual(groups[2]["header.step"].tolist(), [1.0, 5.0])

    def test_match_steps_pairs_equal_steps_only(self):
        import numpy as np
        truth = {"header.step": np.array([0.0, 1.0, 2.0, 3.0, 4.0])}
        other = {"header.step": np.array([1.0, 2.5, 4.0, 9.0])}
        i_truth, i_other = report.match_steps(truth, other)
        self.assertEqual(i_truth.tolist(), [1, 4])
        self.assertEqual(i_other.tolist(), [0, 2])

    def test_wheel_speed_commands(self):
        import numpy as np
        cmd = {"header.step": np.array([0.0, 2.0]), "mode": np.array([0.0, 1.0]), "v": np.array([1.0, 0.0]),
               "omega": np.array([0.2, 0.0]), "v_left": np.array([0.0, 0.8]), "v_right": np.array([0.0, 1.2])}
        state = {"header.step": np.array([0.0, 1.0, 2.0]), "omega": np.array([0.0, 0.1, 0.75])}
        v, omega = report.command_twist(cmd, state)
        self.assertEqual(v.tolist(), [1.0, 1.0])
        self.assertEqual(omega.tolist(), [0.2, 0.75])
        v, omega = report.command_twist(cmd, None)
        self.assertTrue(math.isnan(omega[1]))


if __name__ == "__main__":
    unittest.main()
