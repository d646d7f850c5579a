#pragma once
// The documented exit codes of every meshdev command (README "Exit codes").
namespace meshdev::app {

enum ExitCode : int {
  kOk = 0,            // success
  kRegression = 1,    // meshdev guard: something got worse beyond tolerance
  kUsage = 2,         // bad command line (unknown option, missing argument, bad value)
  kInputError = 3,    // an input file is missing, unreadable or malformed
  kInvalidInput = 4,  // inputs are readable but unusable (no faces, attribute missing on one mesh)
  kWriteError = 5,    // an output could not be written (earlier results are left intact)
  kInternal = 70,     // a bug: an unexpected exception (please report it)
};

}  // namespace meshdev::app
