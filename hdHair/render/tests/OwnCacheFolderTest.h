#pragma once
// A test whose SRBF tables (SrbfTableCache.h) and files live in a temporary
// folder of its own: $HDHAIR_CACHE_DIR points into it while the test runs,
// so no test reads a table another wrote, and nothing outlives the test.

#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "hdHair/environment/tests/LatlongTestTextures.h"

namespace hdhair::test {

class OwnCacheFolderTest : public ::testing::Test {
protected:
    void SetUp() override { setenv("HDHAIR_CACHE_DIR", folder_.path("cache").c_str(), 1); }
    void TearDown() override { unsetenv("HDHAIR_CACHE_DIR"); }
    // A file in the test's folder.
    std::string path(const std::string& name) const { return folder_.path(name); }

private:
    TemporaryFolder folder_;
};

}  // namespace hdhair::test
