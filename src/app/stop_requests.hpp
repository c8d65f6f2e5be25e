#pragma once
// Ctrl-C or SIGTERM while a command trains: the first asks the run to stop within a collection
// step or a learning minibatch and save its last completed iteration (TrainOptions::stop_requests);
// a second exits at once (the checkpoint on disk stays: every write of it is atomic).
namespace mimic::app {

void handle_stop_signals();
int stop_requests();  // how many have come

}  // namespace mimic::app
