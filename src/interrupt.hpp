// Interruption of the streaming commands (query, scene): SIGINT and SIGTERM end a run at a line
// boundary, never inside an output line.
//
// While the command waits for input, every answered line has already been written and flushed,
// so the signal ends the process at once (the lines read but not yet answered are dropped).
// Otherwise it only raises a flag: the command finishes the lines in progress, writes every
// complete answered line, flushes, and exits with 128 + the signal's number (130, 143).
// (main() ignores SIGPIPE for every command, so a closed output is a write error with a
// message, not a silent death.)
#pragma once

namespace certcyl::cli {

// Installs the handlers (idempotent).
void install_interrupt_handlers();

// The signal that asked the run to stop, or 0.
int interrupt_signal();

// Brackets a blocking read during which the process may end at once on a signal: every
// answered line must have been flushed before.
class InterruptibleRead {
 public:
  InterruptibleRead();
  ~InterruptibleRead();
  InterruptibleRead(const InterruptibleRead&) = delete;
  InterruptibleRead& operator=(const InterruptibleRead&) = delete;
};

}  // namespace certcyl::cli
