// Comparing the digests of what hosts of one run loaded (runtime/bus/run_digest.hpp).
#include "runtime/bus/run_digest.hpp"

#include <gtest/gtest.h>

namespace robodds {
namespace {

const RunDigest kOwn = {{"scenario", "/x/s.yaml", "aaaa"}, {"options", "seed=1 duration_s=5", "bbbb"}, {"qos:q.xml", "/x/q.xml", "cccc"}};

PeerDigest peer(const std::string& host, std::map<std::string, std::string> entries) { return PeerDigest{host, std::move(entries)}; }

const std::map<std::string, std::string> kSame = {{"scenario", "aaaa"}, {"options", "bbbb"}, {"qos:q.xml", "cccc"}};

TEST(RunDigest, TheDifferenceNamesTheHostAndTheFile) {
  EXPECT_EQ(digest_difference(kOwn, peer("'control'", kSame)), "");
  auto other = kSame;
  other["scenario"] = "dddd";
  EXPECT_EQ(digest_difference(kOwn, peer("'control'", other)),
            "host 'control' loaded a different scenario file than this host's /x/s.yaml (sha256 aaaa here, dddd there)");
  other = kSame;
  other["qos:q.xml"] = "dddd";
  EXPECT_EQ(digest_difference(kOwn, peer("'sim'", other)),
            "host 'sim' loaded a different QoS file than this host's /x/q.xml (sha256 cccc here, dddd there)");
  other = kSame;
  other["options"] = "dddd";
  EXPECT_NE(digest_difference(kOwn, peer("'sim'", other)).find("different run options (--seed, --duration, --set) than this host's seed=1"),
            std::string::npos);
  other = kSame;
  other.erase("qos:q.xml");
  EXPECT_EQ(digest_difference(kOwn, peer("'sim'", other)), "host 'sim' did not load the QoS file /x/q.xml that this host loaded");
  other = kSame;
  other["qos:extra.xml"] = "eeee";
  EXPECT_EQ(digest_difference(kOwn, peer("'sim'", other)), "host 'sim' loaded a QoS file 'extra.xml' that this host did not load");
}

TEST(RunDigest, TheOutnumberedHostIsTheOddOneATieIsNot) {
  auto other = kSame;
  other["scenario"] = "dddd";
  // This host alone against two that agree with each other: it is the odd one.
  DigestVerdict v = judge_digests(kOwn, {peer("'a'", other), peer("'b'", other)});
  EXPECT_TRUE(v.outnumbered());
  EXPECT_EQ(v.differing_hosts, (std::vector<std::string>{"'a'", "'b'"}));
  // With one that agrees and one that differs: not outnumbered (it names the odd one).
  v = judge_digests(kOwn, {peer("'a'", kSame), peer("'b'", other)});
  EXPECT_FALSE(v.outnumbered());
  EXPECT_EQ(v.agreeing, 2u);
  EXPECT_NE(v.difference.find("host 'b'"), std::string::npos);
  // One against one: a tie, no one is outnumbered.
  EXPECT_FALSE(judge_digests(kOwn, {peer("'a'", other)}).outnumbered());
  // Two that differ from this host and from each other: each digest has one host, a tie.
  auto third = kSame;
  third["options"] = "ffff";
  EXPECT_FALSE(judge_digests(kOwn, {peer("'a'", other), peer("'b'", third)}).outnumbered());
  EXPECT_TRUE(judge_digests(kOwn, {peer("'a'", kSame)}).difference.empty());
}

TEST(RunDigest, LabelsKeepOnlyWhatTheAnnouncementCarries) {
  EXPECT_EQ(digest_label("qos", "my qos;v=2.xml"), "qos:my_qos_v_2.xml");
}

}  // namespace
}  // namespace robodds
