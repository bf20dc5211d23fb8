!> Problems found by every rank in its part of a mesh file (reads by ranges):
!> merged so that every rank holds the same messages, in the order a single
!> reader of the whole file finds them.
module mesh_report
  use core_kinds, only: i8
  use core_status, only: status_t
  use parallel_env, only: par_sum
  use parallel_route, only: par_allgather_text
  implicit none
  private
  public :: merge_capped, keyed_report_t

  !> Problems of a kind reported one by one before a summary line.
  integer, parameter, public :: MAX_REPORT = 10
  !> Length of a merged message (core_status keeps 400 characters).
  integer, parameter, public :: LINE_LEN = 400
  integer, parameter :: KEY_LEN = 20

  !> This rank's problems of one kind whose order is a key (a position in
  !> the file) that does not follow the ranks: the MAX_REPORT with the
  !> smallest keys are kept.
  type :: keyed_report_t
    integer :: n = 0 !< problems found
    integer(i8) :: key(MAX_REPORT) = 0
    character(len=LINE_LEN) :: line(MAX_REPORT) = ''
  contains
    procedure :: add => keyed_add
    procedure :: merge => keyed_merge
  end type keyed_report_t

contains

  !> Problems of one kind found by every rank in its range, rank order being
  !> file order: the first MAX_REPORT over all ranks, then the count of the
  !> rest, the same on every rank. lines(:min(n, MAX_REPORT)) are this rank's.
  subroutine merge_capped(status, prefix, lines, n, what)
    type(status_t), intent(inout) :: status
    character(len=*), intent(in) :: prefix, what
    character(len=LINE_LEN), intent(in) :: lines(:)
    integer, intent(in) :: n
    character(len=LINE_LEN), allocatable :: all(:)
    integer :: i, total
    call par_allgather_text(lines(:min(n, MAX_REPORT)), all)
    total = par_sum(n)
    do i = 1, min(size(all), MAX_REPORT)
      call status%add(trim(all(i)))
    end do
    call status%add_more(prefix, total, MAX_REPORT, what)
  end subroutine merge_capped

  !> One problem at position key (kept if among the MAX_REPORT smallest).
  subroutine keyed_add(this, key, line)
    class(keyed_report_t), intent(inout) :: this
    integer(i8), intent(in) :: key
    character(len=*), intent(in) :: line
    integer :: m, i
    this%n = this%n + 1
    m = min(this%n - 1, MAX_REPORT)
    if (m == MAX_REPORT) then
      if (key >= this%key(m)) return
      m = m - 1
    end if
    i = m
    do while (i >= 1)
      if (this%key(i) <= key) exit
      this%key(i + 1) = this%key(i)
      this%line(i + 1) = this%line(i)
      i = i - 1
    end do
    this%key(i + 1) = key
    this%line(i + 1) = line
  end subroutine keyed_add

  !> The MAX_REPORT problems with the smallest keys over all ranks, then the
  !> count of the rest, into status on every rank.
  subroutine keyed_merge(this, status, prefix, what)
    class(keyed_report_t), intent(in) :: this
    type(status_t), intent(inout) :: status
    character(len=*), intent(in) :: prefix, what
    character(len=KEY_LEN + LINE_LEN), allocatable :: mine(:), all(:)
    character(len=KEY_LEN + LINE_LEN) :: swap
    integer :: i, j, m
    m = min(this%n, MAX_REPORT)
    allocate(mine(m))
    do i = 1, m
      write(mine(i)(1:KEY_LEN), '(i20.20)') this%key(i)
      mine(i)(KEY_LEN + 1:) = this%line(i)
    end do
    call par_allgather_text(mine, all)
    ! (keys are non-negative: their zero-padded texts sort as the numbers)
    do i = 2, size(all)
      swap = all(i)
      j = i - 1
      do while (j >= 1)
        if (llt(all(j)(1:KEY_LEN), swap(1:KEY_LEN)) .or. all(j)(1:KEY_LEN) == &
            swap(1:KEY_LEN)) exit
        all(j + 1) = all(j)
        j = j - 1
      end do
      all(j + 1) = swap
    end do
    do i = 1, min(size(all), MAX_REPORT)
      call status%add(trim(all(i)(KEY_LEN + 1:)))
    end do
    call status%add_more(prefix, par_sum(this%n), MAX_REPORT, what)
  end subroutine keyed_merge

end module mesh_report
