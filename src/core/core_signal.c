/* Batch use: SIGTERM, SIGUSR1 and SIGUSR2 request a clean stop.
 *
 * The handler only records the signal number in a volatile sig_atomic_t (the
 * one thing a handler may safely do); the time loop polls it through
 * impact3d_signal_caught() and stops at the end of the cycle with a restart
 * dump. Bound to Fortran by module core_signal. No MPI here. */
#include <signal.h>
#include <string.h>

static volatile sig_atomic_t caught = 0;

static void on_signal(int signum)
{
  /* Keep the first signal; a second one changes nothing. */
  if (caught == 0) caught = signum;
}

/* Install the handler for SIGTERM, SIGUSR1 and SIGUSR2; 0 on success, else
 * the number of signals whose handler could not be installed. */
int impact3d_signal_install(void)
{
  const int signals[3] = {SIGTERM, SIGUSR1, SIGUSR2};
  struct sigaction action;
  int i, failed = 0;

  memset(&action, 0, sizeof action);
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  /* Restart interrupted system calls: MPI and HDF5 I/O must not see EINTR. */
  action.sa_flags = SA_RESTART;
  for (i = 0; i < 3; ++i) {
    if (sigaction(signals[i], &action, NULL) != 0) ++failed;
  }
  return failed;
}

/* The signal caught so far, 0 if none. */
int impact3d_signal_caught(void)
{
  return (int)caught;
}

/* Name of a handled signal ('SIGTERM', ...), blank-padded into name(1:len). */
void impact3d_signal_name(int signum, char *name, int len)
{
  const char *text = "signal";
  int i, n;

  if (signum == SIGTERM) text = "SIGTERM";
  else if (signum == SIGUSR1) text = "SIGUSR1";
  else if (signum == SIGUSR2) text = "SIGUSR2";
  n = (int)strlen(text);
  for (i = 0; i < len; ++i) name[i] = i < n ? text[i] : ' ';
}

