// Linked into every test executable: a test process that dies of a fatal signal says where
// (common/crash_report.h), so that a failure seen once on a CI machine can be read.
#include <errno.h>  // program_invocation_short_name

#include "common/crash_report.h"

namespace {

struct InstallCrashReport {
  InstallCrashReport() { wb::installCrashReport(program_invocation_short_name); }
} installCrashReport;

}  // namespace
