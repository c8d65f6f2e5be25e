#pragma once
// Ctrl-C or SIGTERM while a command trains: the first asks the run to stop within a collection
// step or a learning minibatch and save its last completed iteration (TrainOptions::stop_requests);
// a second exits at once (the checkpoint on disk stays: every write of it is atomic). A command
// that stopped early this way exits with 128 + the first signal's number (130 for Ctrl-C, 143 for
// SIGTERM), the shell's convention, so that a script does not go on to use what it did not make.
namespace mimic::app {

void handle_stop_signals();
// Once the work a stop would have cut short is done: a signal ends the program again at once, and
// a request that came too late to stop anything is forgotten (the exit status says finished).
void release_stop_signals();
int stop_requests();  // how many have come
int stop_signal();    // the first one's signal number; 0 where none came

}  // namespace mimic::app
