// The run record hashes the input and every output, so it is built only when it is written
// beside the output or handed back to a batch.
#include "cli/execute.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/test_json.h"
#include "support/test_support.h"

namespace hm::cli {
namespace {

namespace fs = std::filesystem;

TEST(Execute, TheRunRecordIsBuiltOnlyWhenWrittenOrKept) {
  const fs::path dir = test::scratch_dir("cli_execute");
  const std::string igs = (dir / "w.igs").string();
  ExecuteOptions quiet;
  quiet.write_record = false;
  ASSERT_EQ(execute_args({"-q", "generate", "wigley", "--patches", "2", "-o", igs}, "test", quiet)
                .exit_code,
            0);
  const std::string out = (dir / "w.obj").string();
  const fs::path written = dir / "w.run.json";
  const std::vector<std::string> words = {"-q", "merge", igs, "-o", out};

  ExecuteResult none = execute_args(words, "test", quiet);
  ASSERT_EQ(none.exit_code, 0);
  EXPECT_TRUE(none.record.is_null());
  EXPECT_FALSE(fs::exists(written));

  ExecuteOptions keep = quiet;
  keep.keep_record = true;
  ExecuteResult kept = execute_args(words, "test", keep);
  ASSERT_EQ(kept.exit_code, 0);
  ASSERT_TRUE(kept.record.is_object());
  const std::string sha = kept.record["input"]["sha256"].get<std::string>();
  EXPECT_EQ(sha.size(), 64u);
  EXPECT_FALSE(fs::exists(written));

  ExecuteResult plain = execute_args(words, "test", {});
  ASSERT_EQ(plain.exit_code, 0);
  EXPECT_TRUE(plain.record.is_null());
  ASSERT_TRUE(fs::exists(written));
  EXPECT_EQ(test::read_json(written)["input"]["sha256"], sha);
}

}  // namespace
}  // namespace hm::cli
