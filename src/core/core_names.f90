!> Answers to an unknown name in the deck (a block, material, face set):
!> name_hint(name, valid) gives the valid names and the closest of them, for
!> the end of the message that refuses the name, e.g.
!>   '&region(2): block: ''rdo'' is not a block of this deck'//name_hint('rdo', names)
!> reads "... (valid: plate, rod; did you mean 'rod'?)". The closest is the
!> one with the fewest single-character edits (insert, delete, replace),
!> compared in lower case; ties go to the first in valid's order.
module core_names
  use core_text, only: to_lower
  implicit none
  private
  public :: name_hint, name_distance

  !> At most this many valid names are listed (then '... (N in all)').
  integer, parameter :: LIST_MAX = 24

contains

  !> ' (valid: a, b, c; did you mean ''b''?)', or ' (there are none)' when
  !> valid is empty.
  function name_hint(name, valid) result(text)
    character(len=*), intent(in) :: name
    character(len=*), intent(in) :: valid(:)
    character(len=:), allocatable :: text
    integer :: i, best, d, dbest
    if (size(valid) == 0) then
      text = ' (there are none)'
      return
    end if
    text = ' (valid: '
    do i = 1, min(size(valid), LIST_MAX)
      if (i > 1) text = text//', '
      text = text//trim(valid(i))
    end do
    if (size(valid) > LIST_MAX) then
      block
        character(len=16) :: count
        write(count, '(i0)') size(valid)
        text = text//', ... ('//trim(count)//' in all)'
      end block
    end if
    best = 1
    dbest = huge(1)
    do i = 1, size(valid)
      d = name_distance(name, valid(i))
      if (d < dbest) then
        dbest = d
        best = i
      end if
    end do
    text = text//'; did you mean '''//trim(valid(best))//'''?)'
  end function name_hint

  !> Edit (Levenshtein) distance of the trimmed, lower-cased names.
  pure integer function name_distance(a, b) result(d)
    character(len=*), intent(in) :: a, b
    character(len=len_trim(a)) :: x
    character(len=len_trim(b)) :: y
    integer :: row(0:len_trim(b)), i, j, diagonal, above
    x = to_lower(trim(a))
    y = to_lower(trim(b))
    do j = 0, len(y)
      row(j) = j
    end do
    do i = 1, len(x)
      diagonal = row(0)
      row(0) = i
      do j = 1, len(y)
        above = row(j)
        row(j) = min(row(j) + 1, row(j - 1) + 1, diagonal + merge(0, 1, x(i:i) == y(j:j)))
        diagonal = above
      end do
    end do
    d = row(len(y))
  end function name_distance

end module core_names
