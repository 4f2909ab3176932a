// The wire contract's comments name real things: every sampler name the
// proto gives as an example is one the server accepts (issue 15 found
// "owen_sobol" where the server wants "owen-sobol").
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "core/sampling/samplers.h"

namespace alignset {
namespace {

TEST(ProtoComments, SamplerExamplesAreRealSamplerNames) {
  std::ifstream in(std::string(ALIGNSET_SOURCE_DIR) + "/proto/alignset/v1/alignset.proto");
  ASSERT_TRUE(in);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string proto = ss.str();
  const size_t field = proto.find("string sampler = 1;");
  ASSERT_NE(field, std::string::npos);
  const size_t message = proto.rfind("message SamplesRequest", field);
  ASSERT_NE(message, std::string::npos);
  const std::string comment = proto.substr(message, field - message);
  const std::vector<std::string> known = SamplerNames();
  int examples = 0;
  const std::regex quoted("\"([a-z0-9_-]+)\"");
  for (auto it = std::sregex_iterator(comment.begin(), comment.end(), quoted);
       it != std::sregex_iterator(); ++it) {
    const std::string name = (*it)[1];
    EXPECT_NE(std::find(known.begin(), known.end(), name), known.end()) << name;
    ++examples;
  }
  EXPECT_GE(examples, 3);
}

}  // namespace
}  // namespace alignset
