// Progress on stderr while a long render runs, only when stderr is a terminal.
#pragma once

namespace photovr {

void reportProgress(double fraction, double raysPerSecond, double secondsLeft);

}  // namespace photovr
