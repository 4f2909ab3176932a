#include "server/listen_address.h"

#include <gtest/gtest.h>

namespace alignset::server {
namespace {

TEST(ListenAddressTest, AcceptsHostPortIpv6AndUnixSockets) {
  auto a = ParseListenAddress("127.0.0.1:50051", "--listen");
  ASSERT_TRUE(a.ok());
  EXPECT_EQ(a->host, "127.0.0.1");
  EXPECT_EQ(a->port, 50051);
  a = ParseListenAddress("[::]:0", "--listen");
  ASSERT_TRUE(a.ok()) << a.status().message();
  EXPECT_EQ(a->host, "::");
  EXPECT_EQ(a->port, 0);
  EXPECT_TRUE(ParseListenAddress("localhost:65535", "--listen").ok());
  a = ParseListenAddress("unix:/run/alignset.sock", "--listen");
  ASSERT_TRUE(a.ok());
  EXPECT_TRUE(a->unix_socket);
}

TEST(ListenAddressTest, RefusesWhatGrpcWouldQuietlyReinterpret) {
  for (const char* bad : {"127.0.0.1:80000", "127.0.0.1:65536", "127.0.0.1:-1", "127.0.0.1",
                          "127.0.0.1:", ":50051", "::1:50051", "[::1:50051", "host:5x", "unix:"}) {
    auto a = ParseListenAddress(bad, "--listen");
    EXPECT_FALSE(a.ok()) << bad;
    if (!a.ok()) {
      EXPECT_NE(a.status().message().find("--listen"), std::string::npos);
    }
  }
  EXPECT_NE(ParseListenAddress("127.0.0.1:80000", "--listen").status().message().find("outside 0..65535"),
            std::string::npos);
}

}  // namespace
}  // namespace alignset::server
