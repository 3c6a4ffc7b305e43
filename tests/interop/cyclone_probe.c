/* cyclone_probe: a Cyclone DDS (C API) participant that reads and writes robodds topics, to show
 * and test that another DDS implementation can talk to a robodds run (docs/interop.md).
 *
 *   cyclone_probe read-state --domain D --seconds S [--robot R]
 *       prints every plant/state sample it reads, one line each; exit 0 if it read at least one.
 *   cyclone_probe write-cmd --domain D --robot R --pattern hostile|valid [--linger S]
 *       waits for a plant/cmd reader, writes the pattern, prints one line per sample and
 *       "last_write_ns=<CLOCK_REALTIME ns>" after the last one, then lingers S seconds (the
 *       writer stays alive but silent) and exits.
 *
 * Types come from idl/robodds.idl through Cyclone's idlc at build time (the build tree only).
 * plant/cmd is written with hostile_command.idl, which has the same wire image but a plain
 * integer `mode`, so that a mode outside the CommandMode enum can be sent.
 * QoS: what our readers request (deploy/qos/robodds_qos.xml), see docs/interop.md. */
#define _POSIX_C_SOURCE 200809L
#include <dds/dds.h>
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hostile_command.h"
#include "robodds.h"

#define MATCH_TIMEOUT_S 15

static int usage(const char* why) {
  fprintf(stderr,
          "error: cyclone_probe: %s\n"
          "usage: cyclone_probe read-state --domain D --seconds S [--robot R]\n"
          "       cyclone_probe write-cmd --domain D --robot R --pattern hostile|valid [--linger S]\n",
          why);
  return 2;
}

static int64_t wall_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_REALTIME, &ts);
  return (int64_t)ts.tv_sec * 1000000000LL + ts.tv_nsec;
}

static int parse_double(const char* text, double* out) {
  char* end = NULL;
  errno = 0;
  const double value = strtod(text, &end);
  if (errno != 0 || end == text || *end != '\0' || !isfinite(value) || value < 0.0) {
    return 0;
  }
  *out = value;
  return 1;
}

static int parse_uint(const char* text, unsigned long max, unsigned long* out) {
  char* end = NULL;
  errno = 0;
  const unsigned long value = strtoul(text, &end, 10);
  if (errno != 0 || end == text || *end != '\0' || text[0] == '-' || value > max) {
    return 0;
  }
  *out = value;
  return 1;
}

static void fail_dds(const char* what, dds_return_t rc) {
  fprintf(stderr, "error: cyclone_probe: %s failed: %s\n", what, dds_strretcode(rc));
  exit(1);
}

/* A participant named "cyclone_probe" (robodds logs name a writer by its participant's name). */
static dds_entity_t create_participant(dds_domainid_t domain) {
  dds_qos_t* qos = dds_create_qos();
  dds_qset_entity_name(qos, "cyclone_probe");
  const dds_entity_t participant = dds_create_participant(domain, qos, NULL);
  dds_delete_qos(qos);
  if (participant < 0) fail_dds("dds_create_participant", participant);
  return participant;
}

/* ---- read-state --------------------------------------------------------------------------- */

static int read_state(dds_domainid_t domain, double seconds, long robot) {
  const dds_entity_t participant = create_participant(domain);
  const dds_entity_t topic = dds_create_topic(participant, &robodds_idl_RobotState_desc, "plant/state", NULL, NULL);
  if (topic < 0) fail_dds("dds_create_topic plant/state", topic);
  /* Requested QoS no stronger than the `state` profile offers: reliable, volatile, deadline
   * 500 ms, MANUAL_BY_TOPIC liveliness with a 1 s lease. XCDR1 (our types are @final). */
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 16);
  dds_qset_deadline(qos, DDS_MSECS(500));
  dds_qset_liveliness(qos, DDS_LIVELINESS_MANUAL_BY_TOPIC, DDS_SECS(1));
  dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos, 1, &xcdr1);
  const dds_entity_t reader = dds_create_reader(participant, topic, qos, NULL);
  dds_delete_qos(qos);
  if (reader < 0) fail_dds("dds_create_reader plant/state", reader);

  enum { kBatch = 32 };
  robodds_idl_RobotState samples[kBatch];
  void* buffers[kBatch];
  dds_sample_info_t infos[kBatch];
  for (int i = 0; i < kBatch; ++i) buffers[i] = &samples[i];
  long count = 0;
  const int64_t end = wall_ns() + (int64_t)(seconds * 1e9);
  while (wall_ns() < end) {
    const dds_return_t n = dds_take(reader, buffers, infos, kBatch, kBatch);
    if (n < 0) fail_dds("dds_take plant/state", n);
    for (int i = 0; i < n; ++i) {
      if (!infos[i].valid_data) continue;
      const robodds_idl_RobotState* s = &samples[i];
      if (robot >= 0 && s->robot_id != (uint32_t)robot) continue;
      ++count;
      printf("state robot_id=%" PRIu32 " step=%" PRIu64 " stamp_ns=%" PRId64 " x=%.17g y=%.17g theta=%.17g v=%.17g omega=%.17g\n",
             s->robot_id, s->header.step, s->header.stamp_ns, s->x, s->y, s->theta, s->v, s->omega);
    }
    fflush(stdout);
    dds_sleepfor(DDS_MSECS(10));
  }
  dds_delete(participant);
  if (count == 0) {
    fprintf(stderr, "error: cyclone_probe: read no plant/state sample on domain %d within %.1f s\n", (int)domain, seconds);
    return 1;
  }
  fprintf(stderr, "cyclone_probe: read %ld plant/state samples\n", count);
  return 0;
}

/* ---- write-cmd ---------------------------------------------------------------------------- */

struct Command {
  const char* label;
  uint32_t mode;
  double v, omega, v_left, v_right;
  int stamp; /* 0: wall clock now, 1: INT64_MAX, -1: INT64_MIN */
};

static int write_cmd(dds_domainid_t domain, uint32_t robot, int hostile, double linger_s) {
  const dds_entity_t participant = create_participant(domain);
  /* Same wire image as robodds::idl::VelocityCommand; register it under that name. */
  dds_topic_descriptor_t desc = robodds_probe_RawVelocityCommand_desc;
  desc.m_typename = "robodds::idl::VelocityCommand";
  const dds_entity_t topic = dds_create_topic(participant, &desc, "plant/cmd", NULL, NULL);
  if (topic < 0) fail_dds("dds_create_topic plant/cmd", topic);
  /* Offered QoS at least what the `command` reader profile requests: RELIABLE, VOLATILE or
   * stronger, deadline <= 300 ms, liveliness MANUAL_BY_TOPIC (the strongest kind, so nothing
   * weaker matches) with a lease <= 1 s; XCDR1. A MANUAL_BY_TOPIC writer asserts its
   * liveliness with every write, so it must write at least once per lease. */
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  /* Deeper than the pattern (31 samples): reliable delivery of every sample, none replaced
   * before it was acknowledged, so the plant can count each (tests/integration/interop_cyclone_test.sh). */
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 64);
  dds_qset_deadline(qos, DDS_MSECS(300));
  dds_qset_liveliness(qos, DDS_LIVELINESS_MANUAL_BY_TOPIC, DDS_SECS(1));
  dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos, 1, &xcdr1);
  const dds_entity_t writer = dds_create_writer(participant, topic, qos, NULL);
  dds_delete_qos(qos);
  if (writer < 0) fail_dds("dds_create_writer plant/cmd", writer);

  /* Wait (bounded) for the plant's reader. */
  const int64_t match_deadline = wall_ns() + (int64_t)MATCH_TIMEOUT_S * 1000000000LL;
  for (;;) {
    dds_publication_matched_status_t matched;
    const dds_return_t rc = dds_get_publication_matched_status(writer, &matched);
    if (rc < 0) fail_dds("dds_get_publication_matched_status", rc);
    if (matched.current_count > 0) break;
    if (wall_ns() > match_deadline) {
      dds_offered_incompatible_qos_status_t incompatible;
      dds_get_offered_incompatible_qos_status(writer, &incompatible);
      fprintf(stderr,
              "error: cyclone_probe: no plant/cmd reader matched on domain %d within %d s "
              "(incompatible-QoS readers seen: %" PRIu32 ", last policy id %" PRIu32 ")\n",
              (int)domain, MATCH_TIMEOUT_S, incompatible.total_count, incompatible.last_policy_id);
      dds_delete(participant);
      return 1;
    }
    dds_sleepfor(DDS_MSECS(20));
  }
  /* Matched here means this writer knows the reader; the reader may not know this writer yet
   * and would drop what it sends from an unknown writer (volatile). Give discovery a moment. */
  dds_sleepfor(DDS_MSECS(500));
  fprintf(stderr, "cyclone_probe: plant/cmd reader matched\n");

  static const struct Command kHostile[] = {
      {"nan_v", 0, NAN, 0.0, 0.0, 0.0, 0},
      {"inf_omega", 0, 0.1, INFINITY, 0.0, 0.0, 0},
      {"minus_inf_v", 0, -INFINITY, 0.0, 0.0, 0.0, 0},
      {"nan_wheel", 1, 0.0, 0.0, NAN, 0.1, 0},
      {"absurd_v", 0, 1e300, 0.0, 0.0, 0.0, 0},
      {"absurd_omega", 0, -1e300, 1e300, 0.0, 0.0, 0},
      {"absurd_wheels", 1, 0.0, 0.0, 1e300, -1e300, 0},
      {"bad_enum", 7, 0.3, 0.0, 0.0, 0.0, 0},
      {"stamp_future", 0, 0.3, 0.0, 0.0, 0.0, 1},
      {"stamp_negative", 0, 0.3, 0.0, 0.0, 0.0, -1},
  };
  static const struct Command kValid = {"valid", 0, 0.2, 0.1, 0.0, 0.0, 0};
  /* The hostile pattern ends with a valid-looking command stamped INT64_MAX: a plant that aged
   * commands by their stamp would hold it forever; it must be refused and the plant stop. */
  static const struct Command kLast = {"stamp_future_last", 0, 0.3, 0.0, 0.0, 0.0, 1};
  const int n_hostile = hostile ? (int)(sizeof kHostile / sizeof kHostile[0]) : 0;
  const int n_valid = 20;
  const int n_last = hostile ? 1 : 0;
  uint64_t step = 0;
  int64_t last_write = 0;
  for (int i = 0; i < n_hostile + n_valid + n_last; ++i) {
    const struct Command* c = i < n_hostile ? &kHostile[i] : i < n_hostile + n_valid ? &kValid : &kLast;
    robodds_probe_RawVelocityCommand s;
    memset(&s, 0, sizeof s);
    s.robot_id = robot;
    s.header.step = step;
    s.header.next_step = step + 1;
    last_write = wall_ns();
    s.header.stamp_ns = c->stamp > 0 ? INT64_MAX : c->stamp < 0 ? INT64_MIN : last_write;
    s.mode = c->mode;
    s.v = c->v;
    s.omega = c->omega;
    s.v_left = c->v_left;
    s.v_right = c->v_right;
    const dds_return_t rc = dds_write(writer, &s);
    if (rc < 0) fail_dds("dds_write plant/cmd", rc);
    printf("cmd %s robot_id=%" PRIu32 " step=%" PRIu64 " stamp_ns=%" PRId64 " mode=%" PRIu32 " v=%.17g omega=%.17g v_left=%.17g v_right=%.17g\n",
           c->label, s.robot_id, s.header.step, s.header.stamp_ns, s.mode, s.v, s.omega, s.v_left, s.v_right);
    fflush(stdout);
    ++step;
    dds_sleepfor(DDS_MSECS(50)); /* 20 Hz: within the 300 ms deadline; the plant (100 Hz) sees each */
  }
  printf("last_write_ns=%" PRId64 "\n", last_write);
  fflush(stdout);
  /* Stay alive but silent: the plant must stop on the command's age, not on the writer's end. */
  dds_sleepfor((dds_duration_t)(linger_s * 1e9));
  dds_delete(participant);
  return 0;
}

int main(int argc, char** argv) {
  if (argc < 2) return usage("missing mode");
  const char* mode = argv[1];
  unsigned long domain = 0, robot = 0;
  int have_domain = 0, have_robot = 0;
  double seconds = -1.0, linger = 2.0;
  const char* pattern = NULL;
  for (int i = 2; i < argc; i += 2) {
    if (i + 1 >= argc) return usage("option without a value");
    const char* key = argv[i];
    const char* value = argv[i + 1];
    if (strcmp(key, "--domain") == 0) {
      if (!parse_uint(value, 232, &domain)) return usage("--domain: expected an integer 0..232");
      have_domain = 1;
    } else if (strcmp(key, "--robot") == 0) {
      if (!parse_uint(value, UINT32_MAX, &robot)) return usage("--robot: expected an unsigned 32-bit integer");
      have_robot = 1;
    } else if (strcmp(key, "--seconds") == 0) {
      if (!parse_double(value, &seconds)) return usage("--seconds: expected a finite number >= 0");
    } else if (strcmp(key, "--linger") == 0) {
      if (!parse_double(value, &linger)) return usage("--linger: expected a finite number >= 0");
    } else if (strcmp(key, "--pattern") == 0) {
      pattern = value;
    } else {
      return usage("unknown option");
    }
  }
  if (!have_domain) return usage("--domain is required");
  if (strcmp(mode, "read-state") == 0) {
    if (seconds < 0.0) return usage("read-state: --seconds is required");
    return read_state((dds_domainid_t)domain, seconds, have_robot ? (long)robot : -1);
  }
  if (strcmp(mode, "write-cmd") == 0) {
    if (!have_robot) return usage("write-cmd: --robot is required");
    if (pattern == NULL || (strcmp(pattern, "hostile") != 0 && strcmp(pattern, "valid") != 0)) {
      return usage("write-cmd: --pattern must be hostile or valid");
    }
    return write_cmd((dds_domainid_t)domain, (uint32_t)robot, strcmp(pattern, "hostile") == 0, linger);
  }
  return usage("mode must be read-state or write-cmd");
}
