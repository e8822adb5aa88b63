#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "litamin2/core/covariance_regularizer.hpp"
#include "litamin2/store/keyframe_store.hpp"
#include "support/process_temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using namespace litamin2;
using namespace litamin2::store;
using mapping::LoopEdge;

/// A fresh folder per test (and per process, so concurrent runs do not collide).
fs::path temp_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = litamin2::testing::process_temp_dir("litamin2_store_test_") /
                       (std::string(info->test_suite_name()) + "_" + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

Eigen::Isometry3d random_pose(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().matrix();
  pose.translation() << 10 * n(rng), 10 * n(rng), n(rng);
  return pose;
}

Keyframe make_keyframe(const std::string& stream, std::uint64_t id, std::int64_t stamp_ns,
                       int distributions, std::uint32_t seed = 1) {
  std::mt19937 rng(seed + static_cast<std::uint32_t>(id) * 7919u);
  std::normal_distribution<double> n(0.0, 1.0);
  Keyframe kf;
  kf.key = {stream, id};
  kf.stamp.nanoseconds = stamp_ns;
  kf.odom_pose = random_pose(rng);
  const Matrix6d a = Matrix6d::Random();
  kf.covariance = a * a.transpose() * 1e-4;
  kf.voxel_size = 1.0;
  for (int i = 0; i < distributions; ++i) {
    Distribution d;
    d.mean = Eigen::Vector3d(20 * n(rng), 20 * n(rng), 2 * n(rng));
    const Eigen::Matrix3d b = Eigen::Matrix3d::Random() * 0.2;
    // Well conditioned, so the ICP-term clamp leaves it as it is.
    d.cov = b * b.transpose() + 0.01 * Eigen::Matrix3d::Identity();
    d.count = 5 + i % 50;
    kf.distributions.push_back(d);
  }
  return kf;
}

/// Expects `f` to throw StoreError whose message names `path` and contains `reason`.
template <typename F>
void expect_store_error(F&& f, const fs::path& path, const std::string& reason) {
  try {
    f();
    ADD_FAILURE() << "expected StoreError containing '" << reason << "'";
  } catch (const StoreError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    EXPECT_NE(what.find(reason), std::string::npos) << what;
    EXPECT_EQ(e.path(), path.string());
  }
}

/// Opening `path` in every mode is refused with `reason`, and the file's bytes stay the same.
/// Files whose header claims to be a keyframe store are probed by SQLite, which may create its
/// -wal and -shm files next to them (`side_files_allowed`); other files are not even opened.
void expect_refused_unchanged(const fs::path& path, const std::string& reason,
                              bool side_files_allowed = false) {
  const std::string before = read_bytes(path);
  for (OpenMode mode : {OpenMode::kCreateIfMissing, OpenMode::kMustExist, OpenMode::kReadOnly}) {
    expect_store_error([&] { KeyframeStore::open(path.string(), mode); }, path, reason);
  }
  EXPECT_EQ(read_bytes(path), before) << path << " was modified";
  if (!side_files_allowed) {
    EXPECT_FALSE(fs::exists(path.string() + "-wal"));
    EXPECT_FALSE(fs::exists(path.string() + "-shm"));
  }
}

/// Runs a SQL statement on `path` directly, bypassing the store (to corrupt rows).
void raw_sql(const fs::path& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* message = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message);
  EXPECT_EQ(rc, SQLITE_OK) << (message ? message : "");
  sqlite3_free(message);
  sqlite3_close(db);
}

void expect_same_keyframe_header(const Keyframe& a, const Keyframe& b) {
  EXPECT_EQ(a.key, b.key);
  EXPECT_EQ(a.stamp.nanoseconds, b.stamp.nanoseconds);
  EXPECT_EQ(a.odom_pose.matrix(), b.odom_pose.matrix());
  EXPECT_EQ(a.covariance, b.covariance);
  EXPECT_EQ(a.voxel_size, b.voxel_size);
  EXPECT_EQ(a.distributions.size(), b.distributions.size());
}

TEST(KeyframeStore, RoundTripKeepsPosesCovarianceAndDistributionsToFloatPrecision) {
  const fs::path path = temp_dir() / "store.db";
  const Keyframe kf = make_keyframe("lidar_front", 3, 1'700'000'000'123'456'789, 200);
  {
    KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing);
    EXPECT_TRUE(store.insert_keyframe(kf));
    EXPECT_EQ(store.keyframe_count(), 1u);
    EXPECT_TRUE(store.contains(kf.key));
    EXPECT_FALSE(store.contains({"lidar_front", 4}));
    EXPECT_FALSE(store.contains({"lidar_rear", 3}));
  }
  for (const RegularizerConfig& config :
       {RegularizerConfig{},
        RegularizerConfig{RegularizationMethod::kPlane, 1e-4, 0.3, 1e-3, 1e-6}}) {
    KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kReadOnly);
    const std::vector<Keyframe> loaded = store.load_keyframes(config);
    ASSERT_EQ(loaded.size(), 1u);
    expect_same_keyframe_header(loaded[0], kf);
    for (std::size_t i = 0; i < kf.distributions.size(); ++i) {
      const Distribution& in = kf.distributions[i];
      const Distribution& out = loaded[0].distributions[i];
      EXPECT_EQ(out.count, in.count);
      EXPECT_LT((out.mean - in.mean).cwiseAbs().maxCoeff(), 1e-6 * in.mean.norm() + 1e-12);
      // shape_cov and shape_cov_inv are those the regulariser makes of the stored covariance.
      Eigen::Matrix3d cov, shape, shape_inv;
      regularize_for_terms(config, in.cov.cast<float>().cast<double>(), cov, shape, shape_inv);
      EXPECT_TRUE(out.cov.isApprox(cov, 1e-12));
      EXPECT_TRUE(out.shape_cov.isApprox(shape, 1e-12));
      EXPECT_TRUE(out.shape_cov_inv.isApprox(shape_inv, 1e-12));
      if (config.method == RegularizationMethod::kEigenClamp) {
        EXPECT_TRUE(out.cov.isApprox(in.cov, 1e-6)) << "float precision of the stored triangle";
      }
    }
  }
}

TEST(KeyframeStore, DuplicateInsertsAreIgnoredAndKeepTheFirstKeyframe) {
  const fs::path path = temp_dir() / "store.db";
  KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing);
  const Keyframe a = make_keyframe("s", 0, 100, 10);
  Keyframe a_again = a;
  a_again.stamp.nanoseconds = 999;
  EXPECT_TRUE(store.insert_keyframe(a));
  EXPECT_FALSE(store.insert_keyframe(a));
  EXPECT_FALSE(store.insert_keyframe(a_again));
  const Keyframe b = make_keyframe("s", 1, 200, 10);
  const Keyframe c = make_keyframe("t", 0, 150, 10);
  EXPECT_EQ(store.insert_keyframes({&a, &b, &b, &c}), 2u);
  EXPECT_EQ(store.insert_keyframes({&a, &b, &c}), 0u);
  EXPECT_EQ(store.insert_keyframes({}), 0u);
  EXPECT_EQ(store.keyframe_count(), 3u);
  const std::vector<Keyframe> loaded = store.load_keyframes();
  ASSERT_EQ(loaded.size(), 3u);
  EXPECT_EQ(loaded[0].key, a.key);
  EXPECT_EQ(loaded[0].stamp.nanoseconds, 100);
}

TEST(KeyframeStore, OutOfOrderInsertsLoadInCanonicalOrder) {
  const fs::path path = temp_dir() / "store.db";
  std::vector<Keyframe> keyframes;
  // Equal stamps across streams, so the order also depends on stream and id.
  for (const std::string stream : {"b", "a", "c"}) {
    for (std::uint64_t id = 0; id < 6; ++id) {
      keyframes.push_back(make_keyframe(stream, id, static_cast<std::int64_t>(id / 2) * 100, 3));
    }
  }
  std::vector<Keyframe> shuffled = keyframes;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(42));
  KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing);
  for (std::size_t i = 0; i < shuffled.size(); ++i) {
    if (i % 2 == 0) {
      EXPECT_TRUE(store.insert_keyframe(shuffled[i]));
    } else {
      EXPECT_EQ(store.insert_keyframes({&shuffled[i]}), 1u);
    }
  }
  std::sort(keyframes.begin(), keyframes.end(), canonical_before);
  const std::vector<Keyframe> loaded = store.load_keyframes();
  ASSERT_EQ(loaded.size(), keyframes.size());
  for (std::size_t i = 0; i < loaded.size(); ++i) {
    EXPECT_EQ(loaded[i].key, keyframes[i].key) << i;
    EXPECT_EQ(loaded[i].stamp.nanoseconds, keyframes[i].stamp.nanoseconds) << i;
  }
}

CorrectedPose corrected(const KeyframeKey& key, const Eigen::Isometry3d& pose,
                        const std::string& frame) {
  CorrectedPose p;
  p.key = key;
  p.pose = pose;
  p.frame = frame;
  return p;
}

LoopEdge make_edge(const KeyframeKey& from, const KeyframeKey& to, std::uint32_t seed) {
  std::mt19937 rng(seed);
  LoopEdge e;
  e.from = from;
  e.to = to;
  e.relative = random_pose(rng);
  const Matrix6d a = Matrix6d::Random();
  e.information = a * a.transpose();
  e.fitness = 0.5 + 0.01 * seed;
  e.rmse = 0.1 * seed;
  return e;
}

void expect_same_edges(const std::vector<LoopEdge>& a, const std::vector<LoopEdge>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].from, b[i].from);
    EXPECT_EQ(a[i].to, b[i].to);
    EXPECT_EQ(a[i].relative.matrix(), b[i].relative.matrix());
    EXPECT_EQ(a[i].information, b[i].information);
    EXPECT_EQ(a[i].fitness, b[i].fitness);
    EXPECT_EQ(a[i].rmse, b[i].rmse);
  }
}

TEST(KeyframeStore, LoopEdgesRoundTripAndAreReplacedAsAWhole) {
  const fs::path path = temp_dir() / "store.db";
  KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing);
  EXPECT_TRUE(store.load_loop_edges().empty());
  // Not sorted by key: the order given is the order loaded.
  const std::vector<LoopEdge> first = {make_edge({"b", 2}, {"b", 40}, 1),
                                       make_edge({"a", 0}, {"b", 7}, 2)};
  store.replace_loop_edges(first);
  expect_same_edges(store.load_loop_edges(), first);

  const std::vector<LoopEdge> second = {make_edge({"a", 1}, {"a", 9}, 3)};
  store.replace_loop_edges(second);
  expect_same_edges(store.load_loop_edges(), second);

  // A duplicate edge fails and leaves the previous edges in place (one transaction).
  const std::vector<LoopEdge> duplicated = {make_edge({"c", 1}, {"c", 5}, 4),
                                            make_edge({"c", 1}, {"c", 5}, 5)};
  expect_store_error([&] { store.replace_loop_edges(duplicated); }, path, "given twice");
  expect_same_edges(store.load_loop_edges(), second);

  store.replace_loop_edges({});
  EXPECT_TRUE(store.load_loop_edges().empty());
  store.replace_loop_edges(first);
  store = KeyframeStore::open(path.string(), OpenMode::kMustExist);
  expect_same_edges(store.load_loop_edges(), first);
}

TEST(KeyframeStore, PendingMergesRoundTripInOrderAndAreReplacedAsAWhole) {
  const fs::path path = temp_dir() / "store.db";
  KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing);
  EXPECT_TRUE(store.load_pending_merges().empty());
  const std::vector<LoopEdge> first = {make_edge({"b", 2}, {"a", 40}, 1),
                                       make_edge({"a", 0}, {"b", 7}, 2)};
  store.replace_pending_merges(first);
  expect_same_edges(store.load_pending_merges(), first);
  EXPECT_TRUE(store.load_loop_edges().empty()) << "pending merges are not loop edges";
  const std::vector<LoopEdge> duplicated = {make_edge({"c", 1}, {"d", 5}, 4),
                                            make_edge({"c", 1}, {"d", 5}, 5)};
  expect_store_error([&] { store.replace_pending_merges(duplicated); }, path, "given twice");
  expect_same_edges(store.load_pending_merges(), first);
  store = KeyframeStore::open(path.string(), OpenMode::kMustExist);
  expect_same_edges(store.load_pending_merges(), first);
  expect_same_edges(store.load_graph().pending_merges, first);
}

TEST(KeyframeStore, AVersion2StoreIsReadWithoutPendingMergesAndUpgradedForWriting) {
  const fs::path path = temp_dir() / "v2.db";
  { KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing); }
  raw_sql(path, "DROP TABLE pending_merges; PRAGMA user_version = 2;");
  {
    KeyframeStore read_only = KeyframeStore::open(path.string(), OpenMode::kReadOnly);
    EXPECT_TRUE(read_only.load_pending_merges().empty());
  }
  KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kMustExist);
  const std::vector<LoopEdge> edges = {make_edge({"a", 0}, {"b", 7}, 2)};
  store.replace_pending_merges(edges);
  expect_same_edges(store.load_pending_merges(), edges);
}

TEST(KeyframeStore, CorrectedPosesRoundTripOrderedByKeyAndAreReplacedAsAWhole) {
  const fs::path path = temp_dir() / "store.db";
  KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing);
  std::mt19937 rng(5);
  const std::vector<CorrectedPose> poses = {
      corrected({"b", 1}, random_pose(rng), "a"), corrected({"a", 10}, random_pose(rng), "a"),
      corrected({"a", 2}, random_pose(rng), "a"), corrected({"c", 0}, random_pose(rng), "c")};
  store.replace_corrected_poses(poses);
  const std::vector<CorrectedPose> loaded = store.load_corrected_poses();
  ASSERT_EQ(loaded.size(), 4u);
  const std::vector<std::size_t> by_key = {2, 1, 0, 3};  // a/2, a/10, b/1, c/0
  for (std::size_t i = 0; i < 4; ++i) {
    const CorrectedPose& expected = poses[by_key[i]];
    EXPECT_EQ(loaded[i].key, expected.key);
    EXPECT_EQ(loaded[i].frame, expected.frame);
    EXPECT_EQ(loaded[i].pose.matrix(), expected.pose.matrix());
  }
  const std::vector<CorrectedPose> duplicated = {corrected({"a", 1}, random_pose(rng), "a"),
                                                 corrected({"a", 1}, random_pose(rng), "a")};
  expect_store_error([&] { store.replace_corrected_poses(duplicated); }, path, "given twice");
  EXPECT_EQ(store.load_corrected_poses().size(), 4u);
  store.replace_corrected_poses({poses[3]});
  ASSERT_EQ(store.load_corrected_poses().size(), 1u);
  EXPECT_EQ(store.load_corrected_poses()[0].key, poses[3].key);
}

TEST(KeyframeStore, ReopeningKeepsEverythingAndReadOnlyRefusesWrites) {
  const fs::path path = temp_dir() / "store.db";
  std::vector<Keyframe> keyframes;
  for (std::uint64_t id = 0; id < 5; ++id) keyframes.push_back(make_keyframe("s", id, id, 50));
  const std::vector<LoopEdge> edges = {make_edge({"s", 0}, {"s", 4}, 1)};
  std::mt19937 rng(3);
  const std::vector<CorrectedPose> poses = {corrected({"s", 0}, random_pose(rng), "s")};
  {
    KeyframeStore store =
        KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing, StoreOptions{true, 1000});
    for (const Keyframe& kf : keyframes) store.insert_keyframe(kf);
    store.replace_loop_edges(edges);
    store.replace_corrected_poses(poses);
  }
  // Closing the last connection checkpoints the log into the file and removes it.
  EXPECT_FALSE(fs::exists(path.string() + "-wal"));
  const std::string closed_bytes = read_bytes(path);
  {
    KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kReadOnly);
    const std::vector<Keyframe> loaded = store.load_keyframes();
    ASSERT_EQ(loaded.size(), keyframes.size());
    for (std::size_t i = 0; i < loaded.size(); ++i) {
      expect_same_keyframe_header(loaded[i], keyframes[i]);
    }
    expect_same_edges(store.load_loop_edges(), edges);
    EXPECT_EQ(store.load_corrected_poses().size(), 1u);
    expect_store_error([&] { store.insert_keyframe(make_keyframe("s", 9, 9, 1)); }, path,
                       "read-only");
    expect_store_error([&] { store.replace_loop_edges({}); }, path, "read-only");
    expect_store_error([&] { store.replace_corrected_poses({}); }, path, "read-only");
  }
  EXPECT_EQ(read_bytes(path), closed_bytes);
  KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kMustExist);
  EXPECT_EQ(store.keyframe_count(), keyframes.size());
  EXPECT_TRUE(store.insert_keyframe(make_keyframe("s", 9, 9, 1)));
}

TEST(KeyframeStore, IsMoveOnlyAndAMovedFromStoreSaysSo) {
  static_assert(!std::is_copy_constructible_v<KeyframeStore>);
  static_assert(std::is_nothrow_move_constructible_v<KeyframeStore>);
  const fs::path path = temp_dir() / "store.db";
  KeyframeStore a = KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing);
  KeyframeStore b = std::move(a);
  EXPECT_TRUE(b.insert_keyframe(make_keyframe("s", 0, 0, 1)));
  EXPECT_EQ(b.path(), path.string());
  EXPECT_THROW(a.keyframe_count(), std::logic_error);  // NOLINT(bugprone-use-after-move)
}

/// Child process body: inserts keyframes one transaction each, writing each committed id to
/// `fd`, forever (the parent kills it). Never returns.
[[noreturn]] void insert_until_killed(const std::string& path, int fd) {
  try {
    KeyframeStore store = KeyframeStore::open(path, OpenMode::kCreateIfMissing);
    for (std::uint64_t id = 0;; ++id) {
      store.insert_keyframe(make_keyframe("s", id, static_cast<std::int64_t>(id), 300));
      if (write(fd, &id, sizeof(id)) != static_cast<ssize_t>(sizeof(id))) _exit(3);
    }
  } catch (...) {
    _exit(2);
  }
}

TEST(KeyframeStore, KeepsEveryCommittedKeyframeWhenTheWriterIsKilledMidLoop) {
  const fs::path path = temp_dir() / "store.db";
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    close(fds[0]);
    insert_until_killed(path.string(), fds[1]);
  }
  close(fds[1]);
  // Let the child commit some keyframes, kill it mid-insert, then collect what it reported.
  std::uint64_t id = 0;
  std::uint64_t reported = 0;
  while (reported < 40 && read(fds[0], &id, sizeof(id)) == static_cast<ssize_t>(sizeof(id))) {
    ++reported;
  }
  ASSERT_EQ(kill(child, SIGKILL), 0);
  while (read(fds[0], &id, sizeof(id)) == static_cast<ssize_t>(sizeof(id))) ++reported;
  close(fds[0]);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "child exited with " << WEXITSTATUS(status);
  EXPECT_EQ(WTERMSIG(status), SIGKILL);
  ASSERT_GE(reported, 40u);

  KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kMustExist);
  // Every reported keyframe was committed; at most one more may have committed unreported.
  const std::size_t count = store.keyframe_count();
  EXPECT_GE(count, reported);
  EXPECT_LE(count, reported + 1);
  const std::vector<Keyframe> loaded = store.load_keyframes();
  ASSERT_EQ(loaded.size(), count);
  for (std::size_t i = 0; i < loaded.size(); ++i) {
    EXPECT_EQ(loaded[i].key.id, i);
    EXPECT_EQ(loaded[i].distributions.size(), 300u);
  }
  // The store stays writable after the recovery.
  EXPECT_TRUE(store.insert_keyframe(make_keyframe("s", 100000, 100000, 1)));
}

TEST(KeyframeStore, KeepsSingleAndBatchedCommitsWhenTheWriterKillsItself) {
  const fs::path path = temp_dir() / "store.db";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    try {
      KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing);
      std::vector<Keyframe> batch;
      for (std::uint64_t id = 0; id < 20; ++id) {
        store.insert_keyframe(make_keyframe("single", id, static_cast<std::int64_t>(id), 100));
        batch.push_back(make_keyframe("batch", id, static_cast<std::int64_t>(id), 100));
      }
      std::vector<const Keyframe*> pointers;
      for (const Keyframe& kf : batch) pointers.push_back(&kf);
      store.insert_keyframes(pointers);
      raise(SIGKILL);
    } catch (...) {
    }
    _exit(2);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "child exited with " << WEXITSTATUS(status);
  // The log was not checkpointed: the keyframes are only in it.
  EXPECT_TRUE(fs::exists(path.string() + "-wal"));
  // A read-only open recovers from the log too.
  KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kReadOnly);
  EXPECT_EQ(store.keyframe_count(), 40u);
  EXPECT_EQ(store.load_keyframes().size(), 40u);
}

TEST(KeyframeStore, MissingOrEmptyFilesAreCreatedOnlyWhenAsked) {
  const fs::path dir = temp_dir();
  const fs::path missing = dir / "missing.db";
  expect_store_error([&] { KeyframeStore::open(missing.string(), OpenMode::kMustExist); }, missing,
                     "does not exist");
  expect_store_error([&] { KeyframeStore::open(missing.string(), OpenMode::kReadOnly); }, missing,
                     "does not exist");
  EXPECT_FALSE(fs::exists(missing));

  const fs::path empty = dir / "empty.db";
  write_bytes(empty, "");
  expect_store_error([&] { KeyframeStore::open(empty.string(), OpenMode::kMustExist); }, empty,
                     "empty");
  expect_store_error([&] { KeyframeStore::open(empty.string(), OpenMode::kReadOnly); }, empty,
                     "empty");
  EXPECT_EQ(fs::file_size(empty), 0u);
  KeyframeStore::open(empty.string(), OpenMode::kCreateIfMissing)
      .insert_keyframe(make_keyframe("s", 0, 0, 1));
  EXPECT_EQ(KeyframeStore::open(empty.string(), OpenMode::kMustExist).keyframe_count(), 1u);

  expect_store_error([&] { KeyframeStore::open(dir.string(), OpenMode::kCreateIfMissing); }, dir,
                     "not a regular file");
  expect_store_error([&] { KeyframeStore::open("", OpenMode::kCreateIfMissing); }, "", "empty");
}

TEST(KeyframeStore, FilesThatAreNotSqliteAreRefusedAndLeftUnchanged) {
  const fs::path dir = temp_dir();
  std::mt19937 rng(7);
  std::string random(8192, '\0');
  for (char& c : random) c = static_cast<char>(rng());
  write_bytes(dir / "random.db", random);
  expect_refused_unchanged(dir / "random.db", "not an SQLite database");

  write_bytes(dir / "text.db", "stream,id,stamp\nlidar,0,1700000000\n" + std::string(200, 'x'));
  expect_refused_unchanged(dir / "text.db", "not an SQLite database");

  write_bytes(dir / "short.db", "SQLite format");
  expect_refused_unchanged(dir / "short.db", "too short");
}

/// A closed store of a few keyframes (big enough for many pages), its bytes.
std::string valid_store_bytes(const fs::path& path) {
  {
    KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing);
    for (std::uint64_t id = 0; id < 10; ++id)
      store.insert_keyframe(make_keyframe("s", id, id, 300));
  }
  return read_bytes(path);
}

TEST(KeyframeStore, TruncatedOrCorruptStoresAreRefusedAndLeftUnchanged) {
  const fs::path dir = temp_dir();
  const std::string bytes = valid_store_bytes(dir / "valid.db");
  ASSERT_GT(bytes.size(), 16u * 4096u);
  write_bytes(dir / "half_pages.db", bytes.substr(0, bytes.size() / 4096 / 2 * 4096));
  expect_refused_unchanged(dir / "half_pages.db", "truncated");
  write_bytes(dir / "mid_page.db", bytes.substr(0, bytes.size() / 2 + 123));
  expect_refused_unchanged(dir / "mid_page.db", "truncated");
  write_bytes(dir / "one_page.db", bytes.substr(0, 4096));
  expect_refused_unchanged(dir / "one_page.db", "truncated");
  // A keyframe store's header followed by garbage: SQLite itself finds it malformed.
  std::mt19937 rng(11);
  std::string garbage = bytes;
  for (std::size_t i = 100; i < garbage.size(); ++i) garbage[i] = static_cast<char>(rng());
  write_bytes(dir / "garbage.db", garbage);
  expect_refused_unchanged(dir / "garbage.db", "not a valid SQLite database", true);
}

TEST(KeyframeStore, OtherApplicationsAndSchemasAreRefusedAndLeftUnchanged) {
  const fs::path dir = temp_dir();
  const std::string bytes = valid_store_bytes(dir / "valid.db");
  // Header fields, big-endian: user_version at offset 60, application_id at offset 68.
  std::string other_app = bytes;
  other_app.replace(68, 4, "\x12\x34\x56\x78", 4);
  write_bytes(dir / "other_app.db", other_app);
  expect_refused_unchanged(dir / "other_app.db", "another application (application_id 0x12345678");

  // A plain SQLite database of someone else (application_id 0, its own tables).
  raw_sql(dir / "plain.db", "CREATE TABLE notes (body TEXT); INSERT INTO notes VALUES ('hi');");
  expect_refused_unchanged(dir / "plain.db", "another application (application_id 0x00000000");

  std::string newer = bytes;
  newer.replace(60, 4, std::string("\x00\x00\x00\x04", 4));
  write_bytes(dir / "newer.db", newer);
  expect_refused_unchanged(dir / "newer.db", "schema version 4 is newer");

  // Our header, but a table dropped.
  write_bytes(dir / "no_table.db", bytes);
  raw_sql(dir / "no_table.db", "DROP TABLE corrected_poses");
  expect_refused_unchanged(dir / "no_table.db", "table corrected_poses is missing", true);

  // The valid store itself opens.
  EXPECT_EQ(KeyframeStore::open((dir / "valid.db").string(), OpenMode::kReadOnly).keyframe_count(),
            10u);
}

TEST(KeyframeStore, CorruptRowsAreReportedWithTheirKey) {
  const fs::path path = temp_dir() / "store.db";
  valid_store_bytes(path);
  raw_sql(path, "UPDATE keyframes SET pose = x'0011' WHERE id = 3");
  expect_store_error(
      [&] { KeyframeStore::open(path.string(), OpenMode::kReadOnly).load_keyframes(); }, path,
      "corrupt keyframe row 's'/3: pose blob has 2 bytes, expected 96");
  raw_sql(path,
          "UPDATE keyframes SET pose = (SELECT pose FROM keyframes WHERE id = 4) WHERE id = 3;"
          "UPDATE keyframes SET distributions = substr(distributions, 1, 41) WHERE id = 7");
  expect_store_error(
      [&] { KeyframeStore::open(path.string(), OpenMode::kReadOnly).load_keyframes(); }, path,
      "'s'/7: distributions blob has 41 bytes, not a multiple of 40");
  raw_sql(path,
          "UPDATE keyframes SET distributions = x'' WHERE id = 7;"
          "UPDATE keyframes SET covariance = 'text' WHERE id = 8");
  expect_store_error(
      [&] { KeyframeStore::open(path.string(), OpenMode::kReadOnly).load_keyframes(); }, path,
      "'s'/8: covariance is not a blob");

  KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kMustExist);
  store.replace_loop_edges({make_edge({"s", 0}, {"s", 9}, 1)});
  store.replace_corrected_poses({corrected({"s", 2}, Eigen::Isometry3d::Identity(), "s")});
  raw_sql(path,
          "UPDATE loop_edges SET information = zeroblob(100);"
          "UPDATE corrected_poses SET pose = zeroblob(95)");
  expect_store_error([&] { store.load_loop_edges(); }, path,
                     "corrupt loop edge row 's'/0 -> 's'/9: 6x6 matrix blob has 100 bytes");
  expect_store_error([&] { store.load_corrected_poses(); }, path,
                     "corrupt corrected pose row 's'/2: pose blob has 95 bytes");
}

TEST(KeyframeStore, InvalidKeyframesAreRefusedAndABatchIsAllOrNothing) {
  const fs::path path = temp_dir() / "store.db";
  KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing);
  Keyframe no_stream = make_keyframe("", 0, 0, 1);
  expect_store_error([&] { store.insert_keyframe(no_stream); }, path, "empty stream name");
  Keyframe huge_id = make_keyframe("s", std::uint64_t{1} << 63, 0, 1);
  expect_store_error([&] { store.insert_keyframe(huge_id); }, path, "largest storable id");
  const Keyframe good = make_keyframe("s", 0, 0, 1);
  Keyframe negative_count = make_keyframe("s", 1, 1, 3);
  negative_count.distributions[2].count = -4;
  expect_store_error(
      [&] {
        store.insert_keyframes({&good, &negative_count});
      },
      path, "keyframe 's'/1: a distribution has a negative point count -4");
  expect_store_error(
      [&] {
        store.insert_keyframes({&good, nullptr});
      },
      path, "null keyframe at index 1");
  EXPECT_EQ(store.keyframe_count(), 0u);
  EXPECT_FALSE(store.contains(huge_id.key));
}

}  // namespace

TEST(KeyframeStore, DescriptorsAreReadBackOneByOneAndTheGraphWithRingKeysOnly) {
  const fs::path path = temp_dir() / "store.db";
  KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing);
  std::vector<Keyframe> keyframes;
  std::vector<mapping::PlaceDescriptor> descriptors;
  for (std::uint64_t id = 0; id < 3; ++id) {
    keyframes.push_back(make_keyframe("s", id, static_cast<std::int64_t>(id) * 100, 10));
    mapping::PlaceDescriptor d;
    d.rings = 2;
    d.sectors = 3;
    d.cells = {1, 0, static_cast<std::uint8_t>(7 + id), 255, 0, 9};
    d.ring_key = {0.5f, 2.0f / 3.0f + static_cast<float>(id)};
    descriptors.push_back(d);
  }
  std::vector<const Keyframe*> to_store;
  std::vector<const mapping::PlaceDescriptor*> described;
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    to_store.push_back(&keyframes[i]);
    described.push_back(&descriptors[i]);
  }
  ASSERT_EQ(store.insert_keyframes(to_store, described), 3u);

  for (std::uint64_t id = 0; id < 3; ++id) {
    const mapping::PlaceDescriptor d = store.load_descriptor({"s", id});
    EXPECT_EQ(d.rings, 2);
    EXPECT_EQ(d.sectors, 3);
    EXPECT_EQ(d.cells, descriptors[id].cells) << id;
    EXPECT_EQ(d.ring_key, descriptors[id].ring_key) << id;
  }
  expect_store_error(
      [&] {
        store.load_descriptor({"s", 3});
      },
      path, "cannot read the descriptor of keyframe 's'/3: no such keyframe");

  const auto with_cells = store.load_graph();
  const auto ring_keys_only = store.load_graph(/*descriptor_cells=*/false);
  ASSERT_EQ(with_cells.nodes.size(), 3u);
  ASSERT_EQ(ring_keys_only.nodes.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_TRUE(ring_keys_only.nodes[i].has_descriptor);
    EXPECT_TRUE(ring_keys_only.nodes[i].node.descriptor.cells.empty());
    EXPECT_EQ(ring_keys_only.nodes[i].node.descriptor.ring_key,
              with_cells.nodes[i].node.descriptor.ring_key);
    EXPECT_EQ(with_cells.nodes[i].node.descriptor.cells.size(), 6u);
  }

  // A node row without a descriptor (a migrated store before its replay) has none to read.
  raw_sql(path, "UPDATE nodes SET descriptor = NULL WHERE id = 1");
  expect_store_error([&] { store.load_descriptor({"s", 1}); }, path, "none stored");
}

/// Expects two load_graph results to hold the same records in the same order.
void expect_same_graph_records(const KeyframeStore::GraphRecords& a,
                               const KeyframeStore::GraphRecords& b) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const auto& x = a.nodes[i];
    const auto& y = b.nodes[i];
    ASSERT_EQ(x.node.key, y.node.key) << i;
    EXPECT_EQ(x.node.stamp.nanoseconds, y.node.stamp.nanoseconds) << i;
    EXPECT_EQ(x.node.odom_pose.matrix(), y.node.odom_pose.matrix()) << i;
    EXPECT_EQ(x.node.pose.matrix(), y.node.pose.matrix()) << i;
    EXPECT_EQ(x.node.covariance, y.node.covariance) << i;
    EXPECT_EQ(x.node.descriptor.ring_key, y.node.descriptor.ring_key) << i;
    EXPECT_EQ(x.node.descriptor.cells, y.node.descriptor.cells) << i;
    EXPECT_EQ(x.has_descriptor, y.has_descriptor) << i;
    EXPECT_EQ(x.has_pose, y.has_pose) << i;
    EXPECT_EQ(x.frame, y.frame) << i;
    ASSERT_EQ(x.map_pose.has_value(), y.map_pose.has_value()) << i;
    if (x.map_pose) {
      EXPECT_EQ(x.map_pose->matrix(), y.map_pose->matrix()) << i;
    }
  }
  expect_same_edges(a.loops, b.loops);
}

TEST(KeyframeStore, TheGraphReadBySeveralConnectionsEqualsOneScan) {
  const fs::path path = temp_dir() / "store.db";
  // Three streams interleaved in arrival order, a descriptor for each keyframe, corrected poses
  // for every third, enough rows for four readers (load_graph: 4096 rows a reader at least).
  constexpr std::uint64_t kPerStream = 7000;
  {
    KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing);
    std::vector<Keyframe> keyframes;
    std::vector<mapping::PlaceDescriptor> descriptors;
    std::vector<CorrectedPose> poses;
    std::mt19937 rng(5);
    for (std::uint64_t id = 0; id < kPerStream; ++id) {
      for (const char* stream : {"b", "a", "c"}) {
        keyframes.push_back(make_keyframe(stream, id, static_cast<std::int64_t>(id) * 100, 1));
        mapping::PlaceDescriptor d;
        d.rings = 2;
        d.sectors = 2;
        d.cells = {static_cast<std::uint8_t>(id % 256), 1, 2, static_cast<std::uint8_t>(stream[0])};
        d.ring_key = {static_cast<float>(id), 0.25f};
        descriptors.push_back(d);
        if (id % 3 == 0) poses.push_back(corrected({stream, id}, random_pose(rng), "a"));
      }
    }
    std::vector<const Keyframe*> to_store;
    std::vector<const mapping::PlaceDescriptor*> described;
    for (std::size_t i = 0; i < keyframes.size(); ++i) {
      to_store.push_back(&keyframes[i]);
      described.push_back(&descriptors[i]);
    }
    ASSERT_EQ(store.insert_keyframes(to_store, described), 3 * kPerStream);
    store.replace_corrected_poses(poses);
    store.replace_loop_edges({make_edge({"a", 0}, {"b", 9}, 1)});
    std::vector<std::pair<KeyframeKey, std::optional<Eigen::Isometry3d>>> fused;
    for (std::uint64_t id = 0; id < kPerStream; id += 5)
      fused.push_back({{"c", id}, random_pose(rng)});
    store.set_map_poses(fused);
  }
  StoreOptions one_reader;
  one_reader.restart_readers = 1;
  StoreOptions four_readers;
  four_readers.restart_readers = 4;
  const auto one =
      KeyframeStore::open(path.string(), OpenMode::kMustExist, one_reader).load_graph();
  ASSERT_EQ(one.nodes.size(), 3 * kPerStream);
  EXPECT_EQ(one.readers, 1);
  // Arrival order, as one scan of the rows reads them.
  EXPECT_EQ(one.nodes[0].node.key, (KeyframeKey{"b", 0}));
  EXPECT_EQ(one.nodes[4].node.key, (KeyframeKey{"a", 1}));
  EXPECT_TRUE(one.nodes[0].has_pose);
  EXPECT_FALSE(one.nodes[3].has_pose);
  EXPECT_TRUE(one.nodes[2].map_pose.has_value());
  EXPECT_FALSE(one.nodes[5].map_pose.has_value());
  EXPECT_EQ(one.loops.size(), 1u);
  {
    KeyframeStore store = KeyframeStore::open(path.string(), OpenMode::kMustExist, four_readers);
    const auto four = store.load_graph();
    EXPECT_EQ(four.readers, 4);
    expect_same_graph_records(four, one);
    // A store opened read-only (another process may be writing it) is read in one scan.
    const auto read_only =
        KeyframeStore::open(path.string(), OpenMode::kReadOnly, four_readers).load_graph();
    EXPECT_EQ(read_only.readers, 1);
    expect_same_graph_records(read_only, one);
    expect_same_graph_records(
        store.load_graph(/*descriptor_cells=*/false),
        KeyframeStore::open(path.string(), OpenMode::kMustExist, one_reader).load_graph(false));
  }

  // A corrupt row in a later reader's range is reported with its key, as by one scan.
  raw_sql(path, "UPDATE nodes SET pose = x'0011' WHERE stream = 'c' AND id = 6000");
  for (const StoreOptions& options : {one_reader, four_readers}) {
    expect_store_error(
        [&] { KeyframeStore::open(path.string(), OpenMode::kMustExist, options).load_graph(); },
        path, "corrupt node row 'c'/6000: pose blob has 2 bytes, expected 96");
  }

  // Rows with a gap in their rowids are read by one scan, in the same order.
  raw_sql(path, "DELETE FROM nodes WHERE stream = 'c' AND id = 6000");
  const auto gap_one =
      KeyframeStore::open(path.string(), OpenMode::kMustExist, one_reader).load_graph();
  ASSERT_EQ(gap_one.nodes.size(), 3 * kPerStream - 1);
  const auto gap_four =
      KeyframeStore::open(path.string(), OpenMode::kMustExist, four_readers).load_graph();
  EXPECT_EQ(gap_four.readers, 1);
  expect_same_graph_records(gap_four, gap_one);
}

TEST(KeyframeStore, PageSizeIsSetAtCreationAndInvalidOptionsAreRefused) {
  const fs::path dir = temp_dir();
  // The page size field of the SQLite header (offset 16, big-endian; 1 means 65536).
  auto page_size_field = [](const fs::path& path) {
    const std::string bytes = read_bytes(path);
    return (static_cast<unsigned char>(bytes.at(16)) << 8) |
           static_cast<unsigned char>(bytes.at(17));
  };
  { KeyframeStore::open((dir / "default.db").string(), OpenMode::kCreateIfMissing); }
  EXPECT_EQ(page_size_field(dir / "default.db"), 1);
  StoreOptions small;
  small.page_size = 4096;
  {
    KeyframeStore store =
        KeyframeStore::open((dir / "small.db").string(), OpenMode::kCreateIfMissing, small);
    store.insert_keyframe(make_keyframe("s", 0, 0, 300));
  }
  EXPECT_EQ(page_size_field(dir / "small.db"), 4096);
  // An existing store keeps its page size.
  {
    KeyframeStore store = KeyframeStore::open((dir / "small.db").string(), OpenMode::kMustExist);
    EXPECT_EQ(store.load_keyframes().size(), 1u);
  }
  EXPECT_EQ(page_size_field(dir / "small.db"), 4096);

  const fs::path path = dir / "refused.db";
  // Each invalid value of one option (set by `set`) is refused with `reason` before any file.
  auto expect_refused = [&](std::initializer_list<int> values, void (*set)(StoreOptions&, int),
                            const std::string& name, const std::string& reason) {
    for (const int value : values) {
      StoreOptions options;
      set(options, value);
      expect_store_error(
          [&] { KeyframeStore::open(path.string(), OpenMode::kCreateIfMissing, options); }, path,
          name + " " + std::to_string(value) + reason);
    }
  };
  expect_refused(
      {0, 65}, [](StoreOptions& o, int v) { o.restart_readers = v; }, "restart_readers",
      " is outside [1, 64]");
  expect_refused(
      {0, 65537}, [](StoreOptions& o, int v) { o.sqlite_cache_mb = v; }, "sqlite_cache_mb",
      " is outside [1, 65536]");
  expect_refused(
      {256, 3000, 131072}, [](StoreOptions& o, int v) { o.page_size = v; }, "page_size",
      " is not a power of two in [512, 65536]");
  EXPECT_FALSE(fs::exists(path));
}
