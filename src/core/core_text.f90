!> Numbers as text for messages, the project's one module for it:
!> to_text(i) for integers (decimal, no blanks), to_text(x) for reals (g0,
!> no blanks), fixed_text(x, decimals) for reals with a fixed number of
!> decimals ('0.13', '3600.00').
module core_text
  use core_kinds, only: rk, i8
  implicit none
  private
  public :: to_text, fixed_text

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

end module core_text
