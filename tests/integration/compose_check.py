#!/usr/bin/env python3
"""Checks one deploy/compose/*.yml file against the repository, and optionally runs it natively.

    compose_check.py ROBODDS SRC COMPOSE_FILE [--run OUT_DIR]

Reads the file through `docker-compose config` (so interpolation and path resolution are
docker-compose's own), then checks that:
  - every robodds service uses the one image built from deploy/docker/Dockerfile, whose
    ENTRYPOINT is `robodds-entrypoint robodds host`, and only one service builds it;
  - there is exactly one service per deployment group of the scenario, plus the coordinator;
  - the scenario, the QoS file and each group component's parameter file are mounted
    read-only from files that exist in the repository, at their paths under /opt/robodds;
  - the participant profile exists in the QoS files the service loads, and is UDP-only on a
    bridge network (shared memory across containers delivers nothing); host networking has
    `ipc: host`;
  - a Discovery Server service listens on the address and port the client profile names (host
    network), or on every address with the clients naming it `discovery:PORT` (bridge).
With --run, starts every robodds service as a local process instead of a container (paths
under /opt/robodds mapped back through the mounts, the results volume to OUT_DIR) and requires
the coordinator to finish the run.
"""
import os
import re
import subprocess
import sys
import time

import yaml

SHARE = "/opt/robodds"
errors = []


def fail(message):
    errors.append(message)


def compose_config(compose_file):
    result = subprocess.run(["docker-compose", "-f", compose_file, "config"], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"FAIL: docker-compose config {compose_file}: {result.stderr.strip()}")
    return yaml.safe_load(result.stdout)


def dockerfile_entrypoint(src):
    text = open(os.path.join(src, "deploy/docker/Dockerfile")).read()
    match = re.search(r'^ENTRYPOINT\s+(\[.*\])\s*$', text, re.M)
    return yaml.safe_load(match.group(1)) if match else None


def registered_types(robodds):
    """The component types `robodds components` lists."""
    out = subprocess.run([robodds, "components"], capture_output=True, text=True, check=True).stdout
    return {line.split()[0] for line in out.splitlines() if line and not line[0].isspace()}


def scenario_groups(path):
    """Group -> component types, with ungrouped components in a group of their own name."""
    doc = yaml.safe_load(open(path))
    types = {c["name"]: c.get("type", c["name"]) for c in doc["components"]}
    groups = {g: [types[c] for c in members] for g, members in (doc.get("groups") or {}).items()}
    placed = {c for members in (doc.get("groups") or {}).values() for c in members}
    for name, type_ in types.items():
        if name not in placed:
            groups[name] = [type_]
    return doc["name"], groups


def bind_mounts(service):
    """Container path -> (host path, read_only) for bind mounts; named volumes -> (None, ro)."""
    mounts = {}
    for v in service.get("volumes", []):
        parts = v.split(":") if isinstance(v, str) else [v["source"], v["target"], "ro" if v.get("read_only") else "rw"]
        source, target, mode = parts[0], parts[1], parts[2] if len(parts) > 2 else "rw"
        mounts[target] = (source if source.startswith("/") else None, mode == "ro")
    return mounts


def host_path(container_path, mounts, out_dir=None):
    """Where a container path comes from: the longest matching mount (None for a named volume)."""
    for target in sorted(mounts, key=len, reverse=True):
        if container_path == target or container_path.startswith(target + "/"):
            source, _ = mounts[target]
            base = source if source is not None else out_dir
            return None if base is None else base + container_path[len(target):]
    return None


def profiles_in(xml_path):
    return set(re.findall(r'<participant\s+profile_name="([^"]+)"', open(xml_path).read()))


def check_robodds_service(name, service, src, types, groups, network_mode):
    mounts = bind_mounts(service)
    for target, (source, read_only) in mounts.items():
        if source is None:
            continue
        if not os.path.exists(source):
            fail(f"{name}: mount source {source} does not exist")
        if not read_only:
            fail(f"{name}: {source} is mounted read-write (expected :ro)")
        if os.path.realpath(source).startswith(os.path.realpath(src) + "/"):
            expected_target = SHARE + "/" + os.path.relpath(os.path.realpath(source), os.path.realpath(src))
            if target != expected_target:
                fail(f"{name}: {source} is mounted at {target}, expected {expected_target}")
    command = service.get("command") or []
    if "--scenario" not in command:
        fail(f"{name}: command has no --scenario: {command}")
        return
    scenario = host_path(command[command.index("--scenario") + 1], mounts)
    if scenario is None or not os.path.isfile(scenario):
        fail(f"{name}: scenario {command[command.index('--scenario') + 1]} is not mounted from the repository")

    env = service.get("environment") or {}
    qos_files = [os.path.join(src, "deploy/qos/robodds_qos.xml")]
    qos_env = env.get("ROBODDS_QOS_FILE")
    if qos_env:
        mapped = host_path(qos_env, mounts)
        if mapped is None or not os.path.isfile(mapped):
            fail(f"{name}: ROBODDS_QOS_FILE {qos_env} is not mounted from a file in the repository")
        else:
            qos_files.append(mapped)
    if host_path(SHARE + "/deploy/qos/robodds_qos.xml", mounts) is None:
        fail(f"{name}: deploy/qos is not mounted")
    profile = env.get("ROBODDS_PARTICIPANT_PROFILE", "robodds.participant")
    if not any(profile in profiles_in(f) for f in qos_files if os.path.isfile(f)):
        fail(f"{name}: participant profile '{profile}' is not defined in {qos_files}")
    if network_mode != "host" and profile == "robodds.participant":
        fail(f"{name}: bridge network with the shared-memory profile (use robodds.participant.udp_only)")
    if not re.fullmatch(r"\d+", str(env.get("ROBODDS_DOMAIN_ID", ""))):
        fail(f"{name}: ROBODDS_DOMAIN_ID is not set to a number: {env.get('ROBODDS_DOMAIN_ID')}")

    if name == "coordinator":
        if "--coordinate" not in command or "--group" in command:
            fail(f"coordinator: expected --coordinate without --group: {command}")
        return None
    if "--group" not in command:
        fail(f"{name}: command has no --group: {command}")
        return None
    group = command[command.index("--group") + 1]
    if group not in groups:
        fail(f"{name}: group '{group}' is not a group of the scenario ({', '.join(groups)})")
        return None
    for type_ in groups[group]:
        if type_ not in types:
            fail(f"{name}: component type '{type_}' is not registered")
    if "--run-id" not in command or "--out" not in command:
        fail(f"{name}: expected --run-id and --out in {command}")
    return group


def check(robodds, src, compose_file):
    config = compose_config(compose_file)
    services = config.get("services", {})
    entrypoint = dockerfile_entrypoint(src)
    if entrypoint != ["robodds-entrypoint", "robodds", "host"]:
        fail(f"Dockerfile ENTRYPOINT is {entrypoint}, expected [robodds-entrypoint, robodds, host]")
    types = registered_types(robodds)
    scenario_file = None
    for service in services.values():
        command = service.get("command") or []
        if "--scenario" in command:
            scenario_file = host_path(command[command.index("--scenario") + 1], bind_mounts(service))
            break
    if scenario_file is None:
        sys.exit(f"FAIL: {compose_file}: no service names a mounted scenario")
    scenario_name, groups = scenario_groups(scenario_file)

    seen_groups = []
    discovery = services.get("discovery")
    builders = [name for name, service in services.items() if service.get("build")]
    if len(builders) != 1:
        fail(f"expected exactly one service with build: (the one image), found {builders}")
    expected_image = os.environ.get("ROBODDS_IMAGE") or "robodds:latest"
    for name, service in services.items():
        if service.get("image") != expected_image:
            fail(f"{name}: image {service.get('image')}, expected {expected_image}")
        build = service.get("build")
        if build is not None and (os.path.realpath(build.get("context", "")) != os.path.realpath(src)
                                  or build.get("dockerfile") != "deploy/docker/Dockerfile"):
            fail(f"{name}: build {build} is not the repository with deploy/docker/Dockerfile")
        network_mode = service.get("network_mode")
        if network_mode == "host" and service.get("ipc") != "host":
            fail(f"{name}: network_mode host without ipc: host (shared memory would match but not deliver)")
        if network_mode != "host" and not service.get("networks"):
            fail(f"{name}: neither the host network nor a user-defined network")
        if name == "discovery":
            continue
        group = check_robodds_service(name, service, src, types, groups, network_mode)
        if group is not None:
            seen_groups.append(group)
    if sorted(seen_groups) != sorted(groups):
        fail(f"services cover groups {sorted(seen_groups)}, the scenario has {sorted(groups)}")
    if "coordinator" not in services:
        fail("no coordinator service")
    if discovery is not None:
        check_discovery(discovery, services, src)
    return config, scenario_name


def check_discovery(discovery, services, src):
    entry = discovery.get("entrypoint") or []
    if entry[:2] != ["fastdds", "discovery"] or "-l" not in entry or "-p" not in entry or "-i" not in entry:
        fail(f"discovery: entrypoint {entry}, expected fastdds discovery -i ID -l ADDRESS -p PORT")
        return
    address, port = entry[entry.index("-l") + 1], entry[entry.index("-p") + 1]
    host_network = discovery.get("network_mode") == "host"
    if not host_network:
        # On the bridge: no fixed address (two deployments side by side); the server listens on
        # every address of its container and the clients name it: ROS_DISCOVERY_SERVER=discovery:PORT.
        if address != "0.0.0.0":
            fail(f"discovery: listens on {address}, expected 0.0.0.0 (the clients reach it by its service name)")
        if "ipv4_address" in str(discovery.get("networks")):
            fail(f"discovery: fixed network address {discovery.get('networks')} (two deployments could not run at once)")
    for name, service in services.items():
        if name == "discovery":
            continue
        env = service.get("environment") or {}
        if not host_network:
            if env.get("ROS_DISCOVERY_SERVER") != f"discovery:{port}":
                fail(f"{name}: ROS_DISCOVERY_SERVER is {env.get('ROS_DISCOVERY_SERVER')}, expected discovery:{port}")
            continue
        qos = host_path(env.get("ROBODDS_QOS_FILE", ""), bind_mounts(service))
        text = open(qos).read() if qos and os.path.isfile(qos) else ""
        if f"<address>{address}</address>" not in text or f"<port>{port}</port>" not in text:
            fail(f"{name}: client profile {qos} does not name the server {address}:{port}")


def last_errors(out_dir, processes):
    """The last error line of each service's log (the scratch directory is gone after a test)."""
    lines = []
    for name in processes:
        with open(os.path.join(out_dir, f"{name}.log"), errors="replace") as log:
            errors = [line.strip() for line in log if "error" in line]
        lines.append(f"{name}: {errors[-1] if errors else '(no error logged)'}")
    return " | ".join(lines)


def run_natively(robodds, src, config, out_dir, timeout_s=600):
    """Each robodds service as a local process: the containers' commands, without containers."""
    processes = {}
    try:
        for name, service in config["services"].items():
            if name == "discovery":
                continue
            mounts = bind_mounts(service)

            def local(value):
                value = str(value)
                if not value.startswith(SHARE + "/"):
                    return value
                mapped = host_path(value, mounts, out_dir)  # a mount, or the results volume
                return mapped if mapped is not None else os.path.join(src, value[len(SHARE) + 1:])  # the image's copy

            args = [local(a) for a in service["command"]]
            env = dict(os.environ, ROBODDS_SHARE_DIR=src)
            env.update({key: local(value) for key, value in (service.get("environment") or {}).items()})
            log = open(os.path.join(out_dir, f"{name}.log"), "w")
            processes[name] = subprocess.Popen([robodds, "host"] + args, env=env, stdout=log, stderr=subprocess.STDOUT)
        deadline = time.time() + timeout_s
        while processes["coordinator"].poll() is None and time.time() < deadline:
            time.sleep(0.1)
        code = processes["coordinator"].poll()
        if code is None:  # paper1_waypoints' lockstep run: ~20 s idle, 5-8 times that beside CPU hogs
            fail(f"native run: the coordinator still running after {timeout_s} s; " + last_errors(out_dir, processes))
        if code != 0:
            fail(f"native run: coordinator exited with {code}; " + last_errors(out_dir, processes))
        for name, p in processes.items():
            try:
                if p.wait(timeout=30) != 0:
                    fail(f"native run: {name} exited with {p.returncode}")
            except subprocess.TimeoutExpired:
                fail(f"native run: {name} still running 30 s after the coordinator finished")
    finally:
        for p in processes.values():
            if p.poll() is None:
                p.terminate()
                try:
                    p.wait(timeout=5)
                except subprocess.TimeoutExpired:
                    p.kill()


def main():
    if len(sys.argv) not in (4, 6):
        sys.exit(__doc__)
    robodds, src, compose_file = sys.argv[1], os.path.realpath(sys.argv[2]), sys.argv[3]
    config, scenario_name = check(robodds, src, compose_file)
    if len(sys.argv) == 6 and sys.argv[4] == "--run" and not errors:
        run_natively(robodds, src, config, sys.argv[5])
    for e in errors:
        print(f"FAIL: {os.path.basename(compose_file)}: {e}", file=sys.stderr)
    if errors:
        sys.exit(1)
    print(f"ok: {os.path.basename(compose_file)}: {len(config['services'])} services for scenario {scenario_name} check out")


if __name__ == "__main__":
    main()
