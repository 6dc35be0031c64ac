#pragma once
// JUnit XML of a test run (what GitLab, Jenkins and GitHub display), in the shape of the common
// JUnit schema (tests/e2e/data/scenarios/junit.xsd): <testsuites> with one <testsuite> per scenario
// file, one <testcase name classname time> per case, with <failure> (an assertion failed, or an
// expected failure passed), <error> (the scenario could not run: its diagnostics) or <skipped>
// (an expected failure, as pytest reports xfail), and the tests/failures/errors/skipped counts.
#include <string>
#include <vector>

#include "scenario/runner.hpp"

namespace virtcom::scenario {

std::string junitXml(const std::vector<CaseResult>& results);

}  // namespace virtcom::scenario
