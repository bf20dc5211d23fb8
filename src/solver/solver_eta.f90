!> Time left in a run, from the recent rate: simulated time per wall-clock
!> second over the last few status intervals (the rate changes during a run,
!> e.g. as a shock sharpens the time step, so the whole-run average lags).
module solver_eta
  use core_kinds, only: rk
  implicit none
  private

  integer, parameter :: NSAMPLE = 6 !< samples kept: the last NSAMPLE - 1 intervals

  !> The last few (wall-clock, simulated) time pairs.
  type, public :: eta_t
    real(rk) :: wall(NSAMPLE) = 0.0_rk
    real(rk) :: time(NSAMPLE) = 0.0_rk
    integer :: n = 0 !< samples held (up to NSAMPLE)
    integer :: last = 0 !< index of the newest
  contains
    procedure :: add => eta_add
    procedure :: seconds_left => eta_seconds_left
  end type eta_t

contains

  !> Record a sample (at the start of the run and at every status line).
  subroutine eta_add(this, wall, time)
    class(eta_t), intent(inout) :: this
    real(rk), intent(in) :: wall, time !< wall-clock seconds, simulated time
    this%last = mod(this%last, NSAMPLE) + 1
    this%wall(this%last) = wall
    this%time(this%last) = time
    this%n = min(this%n + 1, NSAMPLE)
  end subroutine eta_add

  !> Wall-clock seconds to reach t_end at the rate since the oldest sample
  !> held; negative when unknown (fewer than two samples, no progress).
  real(rk) function eta_seconds_left(this, t_end) result(left)
    class(eta_t), intent(in) :: this
    real(rk), intent(in) :: t_end
    integer :: oldest
    real(rk) :: dwall, dtime
    left = -1.0_rk
    if (this%n < 2) return
    oldest = mod(this%last - this%n + NSAMPLE, NSAMPLE) + 1
    dwall = this%wall(this%last) - this%wall(oldest)
    dtime = this%time(this%last) - this%time(oldest)
    if (.not. (dtime > 0.0_rk .and. dwall >= 0.0_rk)) return
    left = max(t_end - this%time(this%last), 0.0_rk) * dwall / dtime
  end function eta_seconds_left

end module solver_eta
