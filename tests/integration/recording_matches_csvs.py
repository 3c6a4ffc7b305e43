#!/usr/bin/env python3
"""A lockstep `robodds run --record` file, as decoded by the official reader (tests/npm/check_mcap.mjs,
one JSON line per message), against the run's CSVs (the evaluator's, one per recorded topic):

  recording_matches_csvs.py JSONL OUT_DIR[:OUT_DIR...] STEP_NS [--no-csv TOPIC]...

(several OUT_DIRs: runs of the same lockstep scenario whose evaluators served different robots;
their rows of one topic are pooled, a row in two of them must be the same.)

- every topic of the file has a CSV in OUT_DIR and every CSV a topic, except the --no-csv topics
  (published but not recordable to CSV: their messages are checked by the caller);
- per topic as many messages as CSV rows, one message per (key members, header.step);
- every CSV column equals the decoded field of the same name (nested fields dotted, arrays name[i],
  sequences one column of ';'-separated items, struct items ':'-separated; doubles exactly, as the
  CSV holds the shortest round-trip text), except the evaluator's own columns (t_s, true_*), and t_s
  is the message's log time;
- log_time = header.step x STEP_NS and publish_time = header.stamp_ns.
Exit 1 with one line naming the topic, row and column at the first disagreement.
"""
import csv
import glob
import json
import os
import sys

KEYS = ("robot_id", "target_id", "peer_id", "header.step")
EVALUATOR_COLUMNS = ("t_s", "true_x", "true_y", "true_theta")  # added by the evaluator, not message fields


def fail(reason):
    print(f"recording_matches_csvs: {reason}", file=sys.stderr)
    sys.exit(1)


def field(value, path):
    """The decoded field at a CSV column name ('header.step', 'ranges', 'p[2]'), or KeyError."""
    for part in path.split("."):
        index = None
        if part.endswith("]"):
            part, index = part[:-1].split("[")
        value = value[part]
        if index is not None:
            value = value[int(index)]
    return value


def same(text, value):
    """CSV text against a decoded value: numbers exactly, booleans as 1/0, sequences item by item."""
    if isinstance(value, list):
        items = text.split(";") if text != "" else []
        return len(items) == len(value) and all(same(t, v) for t, v in zip(items, value))
    if isinstance(value, dict):
        parts = text.split(":")
        return len(parts) == len(value) and all(same(t, v) for t, v in zip(parts, value.values()))
    if isinstance(value, str):
        return text == value
    if isinstance(value, bool):
        return text == ("1" if value else "0")
    return float(text) == float(value)


def main():
    args = sys.argv[1:]
    if len(args) < 3:
        fail("usage: recording_matches_csvs.py JSONL OUT_DIR STEP_NS [--no-csv TOPIC]...")
    jsonl, out_dir, step_ns = args[0], args[1], int(args[2])
    no_csv = {args[i + 1] for i in range(3, len(args) - 1) if args[i] == "--no-csv"}
    by_topic = {}
    for line in open(jsonl):
        m = json.loads(line)
        by_topic.setdefault(m["topic"], []).append(m)
    csvs = {}
    for d in out_dir.split(":"):
        for p in glob.glob(os.path.join(d, "*.csv")):
            csvs.setdefault(os.path.basename(p)[: -len(".csv")], []).append(p)
    for topic in sorted(by_topic):
        if topic in no_csv:
            continue
        paths = csvs.pop(topic.replace("/", "_"), None)
        if paths is None:
            fail(f"{topic}: {len(by_topic[topic])} messages in the file and no CSV in {out_dir}")
        rows, pooled = [], {}
        for path in paths:
            with open(path, newline="") as f:
                for r in csv.DictReader(f):
                    key = tuple(r[k] for k in KEYS if k in r)
                    if key in pooled:
                        if pooled[key] != r:
                            fail(f"{topic}: the CSVs of {out_dir} disagree at {key}")
                        continue
                    pooled[key] = r
                    rows.append(r)
        recorded = by_topic[topic]
        if len(recorded) != len(rows):
            fail(f"{topic}: {len(recorded)} messages in the file, {len(rows)} CSV rows")
        keys = [k for k in KEYS if k in rows[0]] if rows else []
        decoded = {}
        for m in recorded:
            key = tuple(str(field(m["value"], k)) for k in keys)
            if key in decoded:
                fail(f"{topic}: two messages of {dict(zip(keys, key))}")
            decoded[key] = m
        compared = 0
        for n, r in enumerate(rows, start=2):  # line 1 is the header
            key = tuple(r[k] for k in keys)
            m = decoded.get(key)
            if m is None:
                fail(f"{topic}: CSV line {n} ({dict(zip(keys, key))}) has no message in the file")
            for column, text in r.items():
                if column.startswith("true_"):
                    continue  # the peer's true pose, the evaluator's: not in the message
                if column == "t_s":
                    if abs(float(text) * 1e9 - int(m["log_time"])) > 0.5:
                        fail(f"{topic} CSV line {n}: t_s {text}, log_time {m['log_time']} ns")
                    continue
                try:
                    value = field(m["value"], column)
                except (KeyError, IndexError, ValueError):
                    fail(f"{topic}: CSV column '{column}' is no field of the decoded message {json.dumps(m['value'])[:200]}")
                if not same(text, value):
                    fail(f"{topic} CSV line {n}, {column}: CSV {text}, file {json.dumps(value)[:200]}")
                compared += 1
            step = int(r["header.step"])
            if int(m["log_time"]) != step * step_ns:
                fail(f"{topic} CSV line {n}: log_time {m['log_time']} at step {step} (step x {step_ns} ns expected)")
            if int(m["publish_time"]) != int(r["header.stamp_ns"]):
                fail(f"{topic} CSV line {n}: publish_time {m['publish_time']}, stamp {r['header.stamp_ns']}")
        print(f"ok: {topic}: {len(rows)} messages = CSV rows, {compared} values equal (official decoder), "
              f"log_time = step x step_s, publish_time = stamp")
    if csvs:
        fail(f"CSVs without a topic in the file: {sorted(csvs)}")
    missing = sorted(no_csv - set(by_topic))
    if missing:
        fail(f"no messages of {missing} in the file")


if __name__ == "__main__":
    main()
