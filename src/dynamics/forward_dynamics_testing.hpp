// What tests may change in how a simulation runs, none of which changes its answer.
#pragma once

namespace nbar::testing {

// With `every`, a simulation whose rows are made on a second thread has the steps' thread make
// the rows of every other job (the row thread only keeps them), where it otherwise makes a job's
// only while the row thread is behind: the rows must be the same either way.
void make_every_other_job_on_the_steps_thread(bool every);

}  // namespace nbar::testing
