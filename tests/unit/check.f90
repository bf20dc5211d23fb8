!> A small assertion module for the unit tests: each check prints one line,
!> check_summary prints "N passed, M failed" and stops with 1 on failure.
module check
  use, intrinsic :: iso_fortran_env, only: output_unit
  use core_kinds, only: rk
  implicit none
  private
  public :: check_true, check_close, check_summary

  integer :: passed = 0
  integer :: failed = 0

contains

  !> Pass when condition holds.
  subroutine check_true(name, condition)
    character(len=*), intent(in) :: name
    logical, intent(in) :: condition
    if (condition) then
      passed = passed + 1
      write(output_unit, '(a)') 'PASS '//name
    else
      failed = failed + 1
      write(output_unit, '(a)') 'FAIL '//name
    end if
  end subroutine check_true

  !> Pass when |value - expected| <= max(rtol |expected|, atol).
  subroutine check_close(name, value, expected, rtol, atol)
    character(len=*), intent(in) :: name
    real(rk), intent(in) :: value, expected, rtol
    real(rk), intent(in), optional :: atol
    real(rk) :: tol
    tol = rtol * abs(expected)
    if (present(atol)) tol = max(tol, atol)
    if (abs(value - expected) <= tol) then
      passed = passed + 1
      write(output_unit, '(a,es24.16)') 'PASS '//name//': ', value
    else
      failed = failed + 1
      write(output_unit, '(a,es24.16,a,es24.16,a,es10.3)') 'FAIL '//name//': ', value, &
          ' expected ', expected, ' tol ', tol
    end if
  end subroutine check_close

  !> Print the totals; error stop 1 if anything failed.
  subroutine check_summary()
    write(output_unit, '(i0,a,i0,a)') passed, ' passed, ', failed, ' failed'
    if (failed > 0) error stop 1
  end subroutine check_summary

end module check
