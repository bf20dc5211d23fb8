!> Restarting a text file of rows (history.txt, the probe CSVs): a new header,
!> then the earlier run's rows up to the restart cycle, copied byte for byte.
!> The old file is read once, whole, and each kept row is written as it is
!> found: time linear in the file's size, rows of any width.
module io_rows
  use core_kinds, only: i8
  implicit none
  private
  public :: rows_restart, rows_read_file

contains

  !> The whole file at path in text (ok false when it cannot be read).
  subroutine rows_read_file(path, text, ok)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: text
    logical, intent(out) :: ok
    integer :: unit, ios
    integer(i8) :: n
    ok = .false.
    open(newunit=unit, file=path, status='old', action='read', access='stream', &
        form='unformatted', iostat=ios)
    if (ios /= 0) then
      allocate(character(len=0) :: text)
      return
    end if
    inquire(unit=unit, size=n)
    allocate(character(len=max(n, 0_i8)) :: text)
    if (n > 0) read(unit, iostat=ios) text
    close(unit)
    ok = ios == 0
  end subroutine rows_read_file

  !> Write path anew: header, then (when keep_old) the rows of the old file
  !> at path whose first field (up to separator) is a cycle <= last_cycle.
  !> The old file's first line is its header: when need_header is present
  !> the old rows are kept only if that line equals it (same is set to
  !> whether it did; .true. when there was no old file).
  subroutine rows_restart(path, header, keep_old, separator, last_cycle, need_header, same)
    character(len=*), intent(in) :: path, header
    logical, intent(in) :: keep_old !< a restart: keep the earlier run's rows
    character(len=1), intent(in) :: separator !< ends a row's cycle field
    integer(i8), intent(in) :: last_cycle
    character(len=*), intent(in), optional :: need_header
    logical, intent(out), optional :: same
    character(len=:), allocatable :: old
    character(len=1), parameter :: LF = achar(10)
    logical :: exists, ok, match
    integer :: unit
    integer(i8) :: first, last, cut, c
    if (present(same)) same = .true.
    allocate(character(len=0) :: old)
    ok = .false.
    if (keep_old) then
      inquire(file=path, exist=exists)
      if (exists) call rows_read_file(path, old, ok)
    end if
    open(newunit=unit, file=path, status='replace', action='write', access='stream', &
        form='unformatted')
    write(unit) header//LF
    if (ok .and. len(old) > 0) then
      ! The old header: the first line.
      last = index(old, LF, kind=i8)
      if (last == 0) last = len(old) + 1
      match = .true.
      if (present(need_header)) match = old(1:last - 1) == need_header
      if (present(same)) same = match
      if (match) then
        do
          first = last + 1
          if (first > len(old)) exit
          last = index(old(first:), LF, kind=i8) + first - 1
          if (last < first) last = len(old) + 1
          ! A row without its newline (a run killed mid-write) is dropped.
          if (last > len(old)) exit
          cut = index(old(first:last - 1), separator, kind=i8) + first - 1
          if (cut < first) cut = last
          if (cut == first) cycle
          call cycle_of(old(first:cut - 1), c, ok)
          if (ok .and. c <= last_cycle) write(unit) old(first:last)
        end do
      end if
    end if
    close(unit)
  end subroutine rows_restart

  !> The cycle a row starts with: digits only (ok false otherwise, or when
  !> it does not fit 18 digits).
  pure subroutine cycle_of(field, c, ok)
    character(len=*), intent(in) :: field
    integer(i8), intent(out) :: c
    logical, intent(out) :: ok
    integer :: i, d
    c = 0
    ok = len(field) > 0 .and. len(field) <= 18
    if (.not. ok) return
    do i = 1, len(field)
      d = iachar(field(i:i)) - iachar('0')
      if (d < 0 .or. d > 9) then
        ok = .false.
        return
      end if
      c = 10 * c + d
    end do
  end subroutine cycle_of

end module io_rows
