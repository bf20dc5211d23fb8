!> Wall-clock timers for the parts of a cycle.
module core_timer
  use core_kinds, only: rk, i8
  implicit none
  private
  public :: wall_time, timer_t

  !> Accumulating stopwatch.
  type, public :: timer_t
    real(rk) :: total = 0.0_rk !< seconds accumulated
    real(rk) :: started = -1.0_rk !< start of the running interval, < 0 when stopped
  contains
    procedure :: start => timer_start
    procedure :: stop => timer_stop
  end type timer_t

contains

  !> Seconds since an arbitrary origin, from the highest-resolution clock.
  function wall_time() result(t)
    real(rk) :: t
    integer(i8) :: count, rate
    call system_clock(count, rate)
    t = real(count, rk) / real(rate, rk)
  end function wall_time

  !> Start (or restart) the interval.
  subroutine timer_start(this)
    class(timer_t), intent(inout) :: this
    this%started = wall_time()
  end subroutine timer_start

  !> Add the running interval to the total.
  subroutine timer_stop(this)
    class(timer_t), intent(inout) :: this
    if (this%started >= 0.0_rk) this%total = this%total + (wall_time() - this%started)
    this%started = -1.0_rk
  end subroutine timer_stop

end module core_timer
