#include "emoface/core/shard.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "emoface/core/errors.hpp"

namespace emoface::core {
namespace {

TEST(Shard, BlocksTileTheItemsInOrder) {
  // 10 items over 4 shards: floor(i·10/4) = 0, 2, 5, 7, 10 → sizes 2, 3, 2, 3.
  const std::pair<std::size_t, std::size_t> expected[] = {{0, 2}, {2, 5}, {5, 7}, {7, 10}};
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ((Shard{i, 4}.block(10)), expected[i]);
  for (std::size_t total : {0u, 1u, 3u, 7u, 100u, 101u})
    for (std::size_t count : {1u, 2u, 3u, 8u}) {
      std::size_t next = 0;
      for (std::size_t i = 0; i < count; ++i) {
        const auto [first, last] = Shard{i, count}.block(total);
        EXPECT_EQ(first, next);
        EXPECT_LE(last - first, total / count + 1);
        for (std::size_t item = first; item < last; ++item)
          EXPECT_TRUE((Shard{i, count}.owns(item, total)));
        next = last;
      }
      EXPECT_EQ(next, total);
    }
  EXPECT_TRUE((Shard{1, 3}.owns(4)));  // interleaved form: 4 % 3 == 1
}

TEST(Shard, ParsesIOverNAndRejectsTheRest) {
  EXPECT_EQ(parse_shard("2/5").index, 2u);
  EXPECT_EQ(parse_shard("2/5").count, 5u);
  for (const char* bad : {"", "1", "5/5", "1/0", "-1/2", "a/2", "1/2/3", " 1/2", "+1/2", "1/"})
    EXPECT_THROW(parse_shard(bad), InvalidInput) << bad;
}

TEST(Shard, AutoReadsTheSlurmArray) {
  std::map<std::string, std::string> env;
  auto getenv = [&](const char* name) -> const char* {
    auto it = env.find(name);
    return it == env.end() ? nullptr : it->second.c_str();
  };
  EXPECT_THROW(parse_shard("auto", getenv), InvalidInput);
  env = {{"SLURM_ARRAY_TASK_ID", "3"}, {"SLURM_ARRAY_TASK_COUNT", "4"}};
  EXPECT_EQ(parse_shard("auto", getenv).index, 3u);
  EXPECT_EQ(parse_shard("auto", getenv).count, 4u);
  // --array=1-4: ids 1…4, MIN 1 → shards 0…3
  env = {
      {"SLURM_ARRAY_TASK_ID", "1"}, {"SLURM_ARRAY_TASK_COUNT", "4"}, {"SLURM_ARRAY_TASK_MIN", "1"}};
  EXPECT_EQ(parse_shard("auto", getenv).index, 0u);
  env["SLURM_ARRAY_TASK_ID"] = "5";
  EXPECT_THROW(parse_shard("auto", getenv), InvalidInput);
  env["SLURM_ARRAY_TASK_ID"] = "x";
  EXPECT_THROW(parse_shard("auto", getenv), InvalidInput);
}

TEST(MergeShardOutputs, CsvDropsLaterStampsAndHeaders) {
  const std::string stamp = "# emoface 0.1.0\n";
  EXPECT_EQ(merge_shard_outputs({stamp + "id,x\na,1\n", stamp + "id,x\nb,2\n", stamp + "id,x\n",
                                 stamp + "id,x\nc,3\n"}),
            stamp + "id,x\na,1\nb,2\nc,3\n");
  EXPECT_THROW(merge_shard_outputs({stamp + "id,x\na,1\n", stamp + "id,y\nb,2\n"}), InvalidInput);
  EXPECT_EQ(merge_shard_outputs({}), "");
}

TEST(MergeShardOutputs, NdjsonDropsLaterStreamHeaders) {
  const std::string head =
      R"({"format":"emoface.fmcv","version":"1.0","generator":"emoface 0.1.0"})"
      "\n";
  EXPECT_EQ(merge_shard_outputs({head + "{\"a\":1}\n", head + "{\"a\":2}\n{\"a\":3}\n"}),
            head + "{\"a\":1}\n{\"a\":2}\n{\"a\":3}\n");
  // A record that merely has a "format" member is data, not a header.
  EXPECT_EQ(merge_shard_outputs({head, "{\"format\":\"x\",\"a\":1}\n"}),
            head + "{\"format\":\"x\",\"a\":1}\n");
}

}  // namespace
}  // namespace emoface::core
