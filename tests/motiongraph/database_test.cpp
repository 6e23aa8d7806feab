#include "emoface/motiongraph/database.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "emoface/core/errors.hpp"
#include "fixtures.hpp"

namespace emoface::motiongraph {
namespace {

TEST(Label, StringRoundTrip) {
  EXPECT_EQ(all_labels().size(), 8u);
  for (Label l : all_labels()) EXPECT_EQ(label_from_string(to_string(l)), l);
  EXPECT_EQ(to_string(Label::Contempt), "contempt");
  EXPECT_THROW(label_from_string("joy"), InvalidInput);
  EXPECT_THROW(label_from_string("Happiness"), InvalidInput);
}

Database two_sequences() {
  Database db;
  db.landmark_count = 3;
  db.sequences = {test::line_sequence("a", Label::Happiness, 4, 3, 1.0),
                  test::line_sequence("b", Label::Fear, 5, 3, 2.0)};
  return db;
}

TEST(Database, ValidAccepted) { EXPECT_NO_THROW(validate(two_sequences())); }

TEST(Database, BadInputRejected) {
  {
    Database db = two_sequences();
    db.sequences[1].frames[2] = Pose::Zero(4, 2);  // inconsistent landmark count
    EXPECT_THROW(validate(db), InvalidInput);
  }
  {
    Database db = two_sequences();
    db.sequences[0].frames.resize(1);  // one frame
    EXPECT_THROW(validate(db), InvalidInput);
    EXPECT_NO_THROW(validate(db, 1));
    db.sequences[0].frames.clear();
    EXPECT_THROW(validate(db, 1), InvalidInput);
  }
  {
    Database db = two_sequences();
    db.sequences[0].frames[1](0, 1) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(validate(db), InvalidInput);
    db.sequences[0].frames[1](0, 1) = std::numeric_limits<double>::infinity();
    EXPECT_THROW(validate(db), InvalidInput);
  }
  {
    Database db = two_sequences();
    db.sequences[1].id = "a";
    EXPECT_THROW(validate(db), InvalidInput);
    db.sequences[1].id = "";
    EXPECT_THROW(validate(db), InvalidInput);
  }
  {
    Database db = two_sequences();
    db.dimensions = 4;
    EXPECT_THROW(validate(db), InvalidInput);
    db = two_sequences();
    db.frame_rate = 0;
    EXPECT_THROW(validate(db), InvalidInput);
    db = two_sequences();
    db.landmark_ids = {1, 2};
    EXPECT_THROW(validate(db), InvalidInput);
  }
}

}  // namespace
}  // namespace emoface::motiongraph
