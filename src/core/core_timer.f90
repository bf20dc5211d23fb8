!> Wall-clock timers: a stopwatch (timer_t) and a registry of named sections
!> (timers_t) that feeds the run's one timing report. A section may lie within
!> another (the halo exchanges within the step): the report indents it.
module core_timer
  use core_kinds, only: rk, i8
  implicit none
  private
  public :: wall_time, timer_t, timers_t

  !> Accumulating stopwatch.
  type :: timer_t
    real(rk) :: total = 0.0_rk !< seconds accumulated
    real(rk) :: started = -1.0_rk !< start of the running interval, < 0 when stopped
    real(rk) :: last = 0.0_rk !< seconds of the last completed interval
  contains
    procedure :: start => timer_start
    procedure :: stop => timer_stop
  end type timer_t

  !> Longest section name.
  integer, parameter, public :: TIMER_NAME_LEN = 16

  !> Named sections, in the order they were added. Every rank must add the
  !> same names in the same order (the report reduces them by position).
  type :: timers_t
    integer :: count = 0
    character(len=TIMER_NAME_LEN), allocatable :: names(:)
    integer, allocatable :: parent(:) !< index of the enclosing section, 0 for none
    type(timer_t), allocatable :: timer(:)
  contains
    procedure :: add => timers_add
    procedure :: id => timers_id
    procedure :: start => timers_start
    procedure :: stop => timers_stop
    procedure :: total => timers_total
    procedure :: last => timers_last
  end type timers_t

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
    if (this%started >= 0.0_rk) then
      this%last = wall_time() - this%started
      this%total = this%total + this%last
    end if
    this%started = -1.0_rk
  end subroutine timer_stop

  !> Add a section (nothing if it exists), optionally within another one
  !> (added first when it is new).
  subroutine timers_add(this, name, within)
    class(timers_t), intent(inout) :: this
    character(len=*), intent(in) :: name
    character(len=*), intent(in), optional :: within
    integer :: up
    up = 0
    if (present(within)) then
      if (this%id(within) == 0) call append(this, within, 0)
      up = this%id(within)
    end if
    if (this%id(name) == 0) call append(this, name, up)
  end subroutine timers_add

  subroutine append(this, name, up)
    class(timers_t), intent(inout) :: this
    character(len=*), intent(in) :: name
    integer, intent(in) :: up
    character(len=TIMER_NAME_LEN), allocatable :: names(:)
    integer, allocatable :: parent(:)
    type(timer_t), allocatable :: timer(:)
    if (.not. allocated(this%names)) allocate(this%names(0), this%parent(0), this%timer(0))
    allocate(names(this%count + 1), parent(this%count + 1), timer(this%count + 1))
    names(:this%count) = this%names
    parent(:this%count) = this%parent
    timer(:this%count) = this%timer
    names(this%count + 1) = name
    parent(this%count + 1) = up
    call move_alloc(names, this%names)
    call move_alloc(parent, this%parent)
    call move_alloc(timer, this%timer)
    this%count = this%count + 1
  end subroutine append

  !> Index of a section, 0 when there is none of that name.
  integer function timers_id(this, name) result(k)
    class(timers_t), intent(in) :: this
    character(len=*), intent(in) :: name
    do k = 1, this%count
      if (this%names(k) == name) return
    end do
    k = 0
  end function timers_id

  !> Start a section's interval (the section is added when new).
  subroutine timers_start(this, name)
    class(timers_t), intent(inout) :: this
    character(len=*), intent(in) :: name
    call this%add(name)
    call this%timer(this%id(name))%start()
  end subroutine timers_start

  !> Stop a section's interval: its seconds go to the section's total.
  subroutine timers_stop(this, name)
    class(timers_t), intent(inout) :: this
    character(len=*), intent(in) :: name
    integer :: k
    k = this%id(name)
    if (k > 0) call this%timer(k)%stop()
  end subroutine timers_stop

  !> Seconds accumulated in a section (0 when there is none of that name).
  real(rk) function timers_total(this, name) result(t)
    class(timers_t), intent(in) :: this
    character(len=*), intent(in) :: name
    integer :: k
    t = 0.0_rk
    k = this%id(name)
    if (k > 0) t = this%timer(k)%total
  end function timers_total

  !> Seconds of a section's last completed interval.
  real(rk) function timers_last(this, name) result(t)
    class(timers_t), intent(in) :: this
    character(len=*), intent(in) :: name
    integer :: k
    t = 0.0_rk
    k = this%id(name)
    if (k > 0) t = this%timer(k)%last
  end function timers_last

end module core_timer
