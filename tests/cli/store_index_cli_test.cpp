// The store's index (issue 52, items 6 and 7): a measure changed in index.sqlite is found by
// `store check` through the row checksums and repaired by a rerun that names what it repaired; a
// store from before row checksums still opens and checks; a read-only or damaged index says
// what is wrong, which file, and what to do.

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_store_support.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

namespace geotandem {
namespace {

using namespace testing;

// Runs one statement on the index with SQLite itself, as a user or a disk fault would change it.
void change_index(const std::string& store, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((store + "/index.sqlite").c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
  const std::string text = error ? error : "";
  sqlite3_free(error);
  sqlite3_close(db);
  ASSERT_EQ(rc, SQLITE_OK) << text;
}

TEST(StoreIndexCli, AMeasureChangedInTheIndexIsDamagedAndARerunWritesItAgainByName) {
  ScratchDir dir;
  const auto cube = dir.file("cube.raw"), store = dir.file("store");
  synth(cube, 3);
  const std::string extract = "-q extract " + q(cube) + " --iso 0.5 --block-size 32 --out " + q(store);
  ASSERT_EQ(run_geotandem(extract + " --workers 0").exit_code, 0);
  const auto rows = rows_of(store);
  ASSERT_GT(rows.size(), 3u);
  ASSERT_EQ(run_geotandem("-q store check " + q(store)).exit_code, 0);

  // In process, then with workers (the manager repairs through its own committer).
  for (const std::string workers : {"0", "2"}) {
    SCOPED_TRACE("--workers " + workers);
    const auto& victim = rows[workers == "0" ? 1 : 2];
    const auto key = std::to_string(victim["key"].get<std::uint64_t>());
    change_index(store, "UPDATE components SET volume = volume * 1.5 + 1 WHERE key = " + key);
    auto check = run_geotandem("-q store check --json " + q(store));
    EXPECT_EQ(check.exit_code, 4) << check.err;
    const auto report = nlohmann::json::parse(check.out, nullptr, false);
    ASSERT_TRUE(report.is_object()) << check.out;
    ASSERT_EQ(report["damaged"].size(), 1u) << check.out;
    EXPECT_EQ(report["damaged"][0]["key"], victim["key"]);
    EXPECT_NE(report["damaged"][0]["problem"].get<std::string>().find("index row"), std::string::npos) << check.out;
    EXPECT_EQ(report["rows_without_checksum"], 0);

    auto rerun = run_geotandem(extract + " --workers " + workers);
    ASSERT_EQ(rerun.exit_code, 0) << rerun.err;
    EXPECT_NE(rerun.out.find("1 damaged component written again: key " + key + ")"), std::string::npos) << rerun.out;
    EXPECT_EQ(run_geotandem("-q store check " + q(store)).exit_code, 0);
    const auto after = rows_of(store);
    ASSERT_EQ(after.size(), rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
      EXPECT_EQ(after[i]["key"], rows[i]["key"]);
      EXPECT_EQ(after[i]["volume"], rows[i]["volume"]) << "the measure is the extraction's again";
    }
  }
}

TEST(StoreIndexCli, AStoreFromBeforeRowChecksumsOpensAndChecks) {
  ScratchDir dir;
  const auto cube = dir.file("cube.raw"), store = dir.file("store");
  synth(cube, 3);
  ASSERT_EQ(run_geotandem("-q extract " + q(cube) + " --iso 0.5 --out " + q(store)).exit_code, 0);
  const auto rows = rows_of(store);
  change_index(store, "ALTER TABLE components DROP COLUMN row_checksum");
  auto check = run_geotandem("-q store check " + q(store));
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
  EXPECT_NE(check.out.find("no row checksums in this store (written before"), std::string::npos) << check.out;
  EXPECT_NE(check.out.find("all intact"), std::string::npos) << check.out;
  EXPECT_EQ(rows_of(store), rows);
  // Written again: the column is added; the rows already there stay without a checksum.
  auto resumed = run_geotandem("-q extract " + q(cube) + " --iso 0.5 --out " + q(store));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  auto json = run_geotandem("-q store check --json " + q(store));
  EXPECT_EQ(json.exit_code, 0) << json.err;
  EXPECT_EQ(nlohmann::json::parse(json.out)["rows_without_checksum"], rows.size());
}

TEST(StoreIndexCli, AReadOnlyOrDamagedIndexSaysWhatIsWrongWhereAndWhatToDo) {
  ScratchDir dir;
  const auto cube = dir.file("cube.raw"), store = dir.file("store");
  synth(cube, 3);
  const std::string extract = "-q extract " + q(cube) + " --iso 0.5 --out " + q(store);
  ASSERT_EQ(run_geotandem(extract).exit_code, 0);
  const auto index = store + "/index.sqlite";

  // Read-only: root runs the command as another user through a user namespace.
  std::string as_other;
  if (::geteuid() == 0) {
    if (std::system("unshare --user true >/dev/null 2>&1") != 0) GTEST_SKIP() << "no user namespaces here";
    as_other = "unshare --user ";
  }
  namespace fs = std::filesystem;
  fs::permissions(index, fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write,
                  fs::perm_options::remove);
  const std::string base = dir.file("ro");
  const int status = std::system(
      (as_other + "'" + test_paths::binary() + "' " + extract + " >" + base + ".out 2>" + base + ".err </dev/null")
          .c_str());
  fs::permissions(index, fs::perms::owner_write, fs::perm_options::add);
  const std::string err = file_text(base + ".err");
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 3) << err;
  EXPECT_NE(err.find("index.sqlite is read-only"), std::string::npos) << err;
  EXPECT_NE(err.find(index), std::string::npos) << "names the file: " << err;
  EXPECT_NE(err.find("chmod"), std::string::npos) << "says what to do: " << err;
  EXPECT_EQ(err.find("attempt to write a readonly database"), std::string::npos) << err;

  // Damaged: the file's header overwritten.
  {
    std::fstream f(index, std::ios::in | std::ios::out | std::ios::binary);
    f.write("this is no database any more", 28);
  }
  for (const std::string& command : {"-q store ls " + q(store), extract}) {
    auto r = run_geotandem(command);
    EXPECT_EQ(r.exit_code, 4) << command << ": " << r.err;
    EXPECT_NE(r.err.find("the store index is damaged"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(index), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("restore index.sqlite from a copy"), std::string::npos) << r.err;
  }
}

} // namespace
} // namespace geotandem
