!> Status object for anything input-driven: an error count and the messages,
!> so that every problem is reported at once and the caller decides how to stop.
module core_status
  implicit none
  private
  public :: status_t

  integer, parameter :: MAX_MESSAGES = 200

  !> Accumulated problems; `count == 0` means success.
  type, public :: status_t
    integer :: count = 0 !< number of problems found
    character(len=400), allocatable :: messages(:) !< their texts (first MAX_MESSAGES)
  contains
    procedure :: add => status_add
    procedure :: ok => status_ok
    procedure :: clear => status_clear
    procedure :: forget => status_forget
    procedure :: add_capped => status_add_capped
    procedure :: add_more => status_add_more
  end type status_t

contains

  !> Record one problem.
  subroutine status_add(this, text)
    class(status_t), intent(inout) :: this
    character(len=*), intent(in) :: text !< what is wrong, where, what would be valid
    if (.not. allocated(this%messages)) allocate(this%messages(MAX_MESSAGES))
    this%count = this%count + 1
    if (this%count <= MAX_MESSAGES) this%messages(this%count) = text
  end subroutine status_add

  !> One of many problems of a kind (bad elements of a mesh file): n counts
  !> them; only the first cap are recorded, add_more summarises the rest.
  subroutine status_add_capped(this, n, cap, text)
    class(status_t), intent(inout) :: this
    integer, intent(inout) :: n
    integer, intent(in) :: cap
    character(len=*), intent(in) :: text
    n = n + 1
    if (n <= cap) call this%add(text)
  end subroutine status_add_capped

  !> The problems of a kind beyond the first cap, as one message.
  subroutine status_add_more(this, prefix, n, cap, what)
    class(status_t), intent(inout) :: this
    character(len=*), intent(in) :: prefix, what
    integer, intent(in) :: n, cap
    character(len=16) :: more
    if (n <= cap) return
    write(more, '(i0)') n - cap
    call this%add(prefix//'and '//trim(more)//' more '//what)
  end subroutine status_add_more

  !> True when no problem was recorded.
  logical function status_ok(this)
    class(status_t), intent(in) :: this
    status_ok = this%count == 0
  end function status_ok

  !> Forget every recorded problem.
  subroutine status_clear(this)
    class(status_t), intent(inout) :: this
    this%count = 0
    if (allocated(this%messages)) deallocate(this%messages)
  end subroutine status_clear

  !> Forget the problems recorded after the first `after` ones whose text starts
  !> with prefix (consequences of a problem already reported).
  subroutine status_forget(this, after, prefix)
    class(status_t), intent(inout) :: this
    integer, intent(in) :: after !< problems 1..after are kept
    character(len=*), intent(in) :: prefix
    integer :: i, n, stored
    if (.not. allocated(this%messages)) return
    stored = min(this%count, MAX_MESSAGES)
    n = after
    do i = after + 1, stored
      if (index(this%messages(i), prefix) == 1) cycle
      n = n + 1
      this%messages(n) = this%messages(i)
    end do
    this%count = this%count - (stored - n)
  end subroutine status_forget

end module core_status
