!> Numbers as text for messages, the project's one module for it:
!> to_text(i) for integers (decimal, no blanks), to_text(x) for reals (g0,
!> no blanks), fixed_text(x, decimals) for reals with a fixed number of
!> decimals ('0.13', '3600.00'); to_lower(s) a lower-case copy of a string,
!> join(words) the words trimmed and separated by ', '.
module core_text
  use core_kinds, only: rk, i8
  implicit none
  private
  public :: to_text, fixed_text, to_lower, join

  interface to_text
    module procedure int_text, i8_text, real_text
  end interface to_text

contains

  pure function int_text(value) result(text)
    integer, intent(in) :: value
    character(len=:), allocatable :: text
    text = i8_text(int(value, i8))
  end function int_text

  pure function i8_text(value) result(text)
    integer(i8), intent(in) :: value
    character(len=:), allocatable :: text
    character(len=24) :: buffer
    write(buffer, '(i0)') value
    text = trim(buffer)
  end function i8_text

  pure function real_text(value) result(text)
    real(rk), intent(in) :: value
    character(len=:), allocatable :: text
    character(len=40) :: buffer
    write(buffer, '(g0)') value
    text = trim(adjustl(buffer))
  end function real_text

  pure function fixed_text(value, decimals) result(text)
    real(rk), intent(in) :: value
    integer, intent(in) :: decimals
    character(len=:), allocatable :: text
    character(len=40) :: buffer
    character(len=16) :: form
    write(form, '(a,i0,a)') '(f40.', decimals, ')'
    write(buffer, form) value
    text = trim(adjustl(buffer))
  end function fixed_text

  !> Lower-case copy of a string.
  pure function to_lower(text) result(lower)
    character(len=*), intent(in) :: text
    character(len=len(text)) :: lower
    integer :: i, code
    lower = text
    do i = 1, len(text)
      code = iachar(text(i:i))
      if (code >= iachar('A') .and. code <= iachar('Z')) lower(i:i) = achar(code + 32)
    end do
  end function to_lower

  !> The words, trimmed, separated by ', '.
  pure function join(words) result(text)
    character(len=*), intent(in) :: words(:)
    character(len=:), allocatable :: text
    integer :: i
    text = ''
    do i = 1, size(words)
      if (i > 1) text = text//', '
      text = text//trim(words(i))
    end do
  end function join

end module core_text
