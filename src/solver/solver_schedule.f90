!> The run's schedule: each cycle's step (the stable step, limited by growth
!> and the deck's bounds, then landed exactly on the next dump time and on
!> t_end), and which outputs and checks are due: dumps by time interval or by
!> cycles, history and status lines, the stop-file look and the wall-time
!> budget. Restart-aware: the next dump time follows from the current time.
!> No I/O: the caller writes what is due.
module solver_schedule
  use core_kinds, only: rk, i8
  implicit none
  private

  !> The deck's schedule and this cycle's decisions.
  type, public :: schedule_t
    real(rk) :: t_end = 0.0_rk
    real(rk) :: dt_max = huge(1.0_rk), dt_min = 0.0_rk, dt_growth = huge(1.0_rk)
    real(rk) :: dt_initial = 0.0_rk
    real(rk) :: dump_interval = 0.0_rk !< 0: no dumps by time
    integer :: dump_cycles = 0 !< 0: no dumps by cycle
    integer :: history_every = 1, status_every = 1, stop_check_every = 10
    real(rk) :: wall_limit = 0.0_rk !< 0: none
    real(rk) :: next_dump = huge(1.0_rk) !< time of the next interval dump
    ! This cycle.
    real(rk) :: dt_stable = 0.0_rk !< the stable step before landing
    logical :: last = .false. !< this cycle lands on t_end
    logical :: dump_now = .false. !< this cycle lands on next_dump
  contains
    procedure :: start => schedule_start
    procedure :: choose_step => schedule_choose_step
    procedure :: land => schedule_land
    procedure :: shorten => schedule_shorten
    procedure :: history_due => schedule_history_due
    procedure :: status_due => schedule_status_due
    procedure :: dump_reason => schedule_dump_reason
    procedure :: audit_due => schedule_audit_due
    procedure :: stop_check_due => schedule_stop_check_due
    procedure :: wall_stop_due => schedule_wall_stop_due
  end type schedule_t

contains

  !> The first interval dump after the current time (a restart continues the
  !> series).
  subroutine schedule_start(this, time)
    class(schedule_t), intent(inout) :: this
    real(rk), intent(in) :: time
    this%next_dump = huge(1.0_rk)
    if (this%dump_interval > 0.0_rk) this%next_dump = this%dump_interval * &
        (aint(time / this%dump_interval + 1.0e-9_rk) + 1.0_rk)
  end subroutine schedule_start

  !> The step of the cycle from the control's stable step: growth from the
  !> previous step (or the deck's first step), the deck's largest step, then
  !> exact landing on t_end and on the next dump. ok is false when the step
  !> falls below dt_min without landing (a failure).
  subroutine schedule_choose_step(this, dt_control, dt_previous, time, dt, ok)
    class(schedule_t), intent(inout) :: this
    real(rk), intent(in) :: dt_control !< stable step of the control reduction
    real(rk), intent(in) :: dt_previous !< the last cycle's stable step (0: none)
    real(rk), intent(in) :: time
    real(rk), intent(out) :: dt
    logical, intent(out) :: ok
    this%dt_stable = min(dt_control, this%dt_max)
    if (dt_previous > 0.0_rk) then
      this%dt_stable = min(this%dt_stable, this%dt_growth * dt_previous)
    else if (this%dt_initial > 0.0_rk) then
      this%dt_stable = min(this%dt_stable, this%dt_initial)
    end if
    dt = this%dt_stable
    this%last = .false.
    this%dump_now = .false.
    if (this%t_end - time <= dt * (1.0_rk + 1.0e-9_rk)) then
      dt = this%t_end - time
      this%last = .true.
    end if
    if (this%next_dump - time <= dt * (1.0_rk + 1.0e-9_rk)) then
      dt = this%next_dump - time
      this%dump_now = .true.
    end if
    ok = .not. (dt < this%dt_min .and. .not. (this%last .or. this%dump_now))
  end subroutine schedule_choose_step

  !> The cycle's step was cut below the planned one (the contact's impact
  !> limit): it lands on neither t_end nor a dump; a later step does.
  subroutine schedule_shorten(this)
    class(schedule_t), intent(inout) :: this
    this%last = .false.
    this%dump_now = .false.
  end subroutine schedule_shorten

  !> The time after a step of dt from time, landed exactly on t_end or the
  !> dump time it aimed at.

  real(rk) function schedule_land(this, time, dt) result(t)
    class(schedule_t), intent(in) :: this
    real(rk), intent(in) :: time, dt
    t = time + dt
    if (this%last) t = this%t_end
    if (this%dump_now .and. abs(t - this%next_dump) <= 1.0e-9_rk * dt) t = this%next_dump
  end function schedule_land

  logical function schedule_history_due(this, cycle) result(due)
    class(schedule_t), intent(in) :: this
    integer(i8), intent(in) :: cycle
    due = mod(cycle, int(this%history_every, i8)) == 0 .or. this%last
  end function schedule_history_due

  logical function schedule_status_due(this, cycle) result(due)
    class(schedule_t), intent(in) :: this
    integer(i8), intent(in) :: cycle
    due = mod(cycle, int(this%status_every, i8)) == 0 .or. this%last
  end function schedule_status_due

  !> The dump due after this cycle ('interval', 'cycles' or '' for none; the
  !> final dump at t_end is the caller's). An interval dump moves next_dump on.
  function schedule_dump_reason(this, cycle) result(reason)
    class(schedule_t), intent(inout) :: this
    integer(i8), intent(in) :: cycle
    character(len=8) :: reason
    reason = ''
    if (this%dump_now) then
      this%next_dump = this%next_dump + this%dump_interval
      if (.not. this%last) reason = 'interval'
    else if (this%dump_cycles > 0 .and. .not. this%last) then
      if (mod(cycle, int(this%dump_cycles, i8)) == 0) reason = 'cycles'
    end if
  end function schedule_dump_reason

  !> Whether a dump (of any kind, the final one included) ends this cycle:
  !> the contact audit runs before every dump.
  logical function schedule_audit_due(this, cycle) result(due)
    class(schedule_t), intent(in) :: this
    integer(i8), intent(in) :: cycle
    due = this%dump_now .or. this%last
    if (this%dump_cycles > 0) due = due .or. mod(cycle, int(this%dump_cycles, i8)) == 0
  end function schedule_audit_due

  logical function schedule_stop_check_due(this, cycle) result(due)
    class(schedule_t), intent(in) :: this
    integer(i8), intent(in) :: cycle
    due = mod(cycle, int(this%stop_check_every, i8)) == 0
  end function schedule_stop_check_due

  !> Close to the wall-time limit: the elapsed time plus a budget of three
  !> cycles, two dumps and a second would pass it.
  logical function schedule_wall_stop_due(this, elapsed, cycle_wall, dump_wall) result(due)
    class(schedule_t), intent(in) :: this
    real(rk), intent(in) :: elapsed, cycle_wall, dump_wall
    due = .false.
    if (this%wall_limit > 0.0_rk) due = elapsed + 3.0_rk * cycle_wall + 2.0_rk * dump_wall + &
        1.0_rk > this%wall_limit
  end function schedule_wall_stop_due

end module solver_schedule
