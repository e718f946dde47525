// AsyncSink: the samples reach the inner sink in order and whole, the files
// are the same bytes as written directly, and the inner sink's error reaches
// the caller.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "../support/cli.hpp"
#include "towsim/output/async_sink.hpp"
#include "towsim/output/output.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/scenario/scenario.hpp"

namespace fs = std::filesystem;
using towsim::Sample;
using towsim::output::AsyncSink;

namespace {

/// Sample i: its time and a node count that varies (the slots' vectors are
/// reused with other sizes around the ring).
Sample numbered(int i) {
  Sample s;
  s.t = i;
  s.node_pos.assign(static_cast<std::size_t>(i % 7), towsim::Vec3(i, -i, 0.5 * i));
  s.tension.assign(static_cast<std::size_t>(i % 7), 2.0 * i);
  return s;
}

/// A sink that throws on sample `fail_at` (a full disk), keeping the ones before.
class FailingSink : public towsim::MemorySink {
 public:
  explicit FailingSink(int fail_at) : fail_at_(fail_at) {}
  void write(const Sample& s) override {
    if (static_cast<int>(s.t) == fail_at_) throw std::runtime_error("timeseries.csv: No space left on device");
    MemorySink::write(s);
  }

 private:
  int fail_at_;
};

}  // namespace

// More samples than the ring holds (kDepth batches of kBatch), so that every
// slot is reused: the inner sink sees each one, in order, unchanged.
TEST(AsyncSink, PassesEverySampleInOrder) {
  constexpr int kSamples = 1000;
  static_assert(kSamples > static_cast<int>(AsyncSink::kBatch * AsyncSink::kDepth));
  towsim::MemorySink inner;
  {
    AsyncSink sink(inner);
    for (int i = 0; i < kSamples; ++i) sink.write(numbered(i));
    sink.flush();
    ASSERT_EQ(inner.samples.size(), static_cast<std::size_t>(kSamples));  // flush() waits for the writer
  }
  for (int i = 0; i < kSamples; ++i) {
    const Sample& s = inner.samples[static_cast<std::size_t>(i)];
    const Sample want = numbered(i);
    EXPECT_EQ(s.t, want.t);
    ASSERT_EQ(s.node_pos.size(), want.node_pos.size()) << "sample " << i;
    for (std::size_t k = 0; k < s.node_pos.size(); ++k) EXPECT_EQ(s.node_pos[k], want.node_pos[k]);
    EXPECT_EQ(s.tension, want.tension);
  }
}

// A part batch, no flush(): the destructor writes it.
TEST(AsyncSink, DestructorWritesWhatIsPending) {
  towsim::MemorySink inner;
  {
    AsyncSink sink(inner);
    for (int i = 0; i < 5; ++i) sink.write(numbered(i));
  }
  ASSERT_EQ(inner.samples.size(), 5u);
  EXPECT_EQ(inner.samples.back().t, 4.0);
}

// The inner sink throws on sample 100 (in the second batch): the caller gets
// that exception, with its text, from flush(); the samples before it are
// written, none after.
TEST(AsyncSink, InnerErrorReachesTheCaller) {
  FailingSink inner(100);
  AsyncSink sink(inner);
  bool thrown = false;
  try {
    for (int i = 0; i < 300; ++i) sink.write(numbered(i));
    sink.flush();
  } catch (const std::runtime_error& e) {
    thrown = true;
    EXPECT_STREQ(e.what(), "timeseries.csv: No space left on device");
  }
  EXPECT_TRUE(thrown);
  EXPECT_EQ(inner.samples.size(), 100u);
  EXPECT_NO_THROW(sink.flush());  // rethrown once
}

// A whole run (the default example, 30 s) written through the AsyncSink
// gives the same bytes as written directly: the sink only moves the work.
TEST(AsyncSink, RunFilesAreTheSameBytes) {
  const towsim::scenario::Example* ex = nullptr;
  for (const auto& e : towsim::scenario::examples())
    if (e.name == towsim::scenario::kDefaultExample) ex = &e;
  ASSERT_NE(ex, nullptr);
  const auto sc = towsim::scenario::load_scenario_text(ex->yaml, "example.yaml", ex->name, ".",
                                                       {"simulation.duration=30"});
  ASSERT_TRUE(sc.ok());
  const fs::path direct = towsim::testing::fresh_dir("async_direct");
  const fs::path async = towsim::testing::fresh_dir("async_thread");
  {
    towsim::output::RunWriter w(direct.string(), *sc.model, true);
    EXPECT_EQ(towsim::simulate(*sc.model, w).status, "ok");
  }
  {
    towsim::output::RunWriter w(async.string(), *sc.model, true);
    AsyncSink sink(w);
    EXPECT_EQ(towsim::simulate(*sc.model, sink).status, "ok");
  }
  for (const char* f : {"timeseries.csv", "nodes.csv"}) {
    const std::string a = towsim::testing::slurp(direct / f);
    EXPECT_GT(a.size(), 1000u) << f;
    EXPECT_EQ(a, towsim::testing::slurp(async / f)) << f;
  }
  fs::remove_all(direct);
  fs::remove_all(async);
}
