!> Batch use: SIGTERM, SIGUSR1 and SIGUSR2 request a clean stop. The handler
!> (core_signal.c) only records the signal; the time loop polls it. No MPI here.
module core_signal
  use, intrinsic :: iso_c_binding, only: c_int, c_char
  implicit none
  private
  public :: signal_install, signal_caught, signal_name

  interface
    function c_signal_install() result(failed) bind(c, name='impact3d_signal_install')
      import :: c_int
      integer(c_int) :: failed
    end function c_signal_install

    function c_signal_caught() result(signum) bind(c, name='impact3d_signal_caught')
      import :: c_int
      integer(c_int) :: signum
    end function c_signal_caught

    subroutine c_signal_name(signum, name, length) bind(c, name='impact3d_signal_name')
      import :: c_int, c_char
      integer(c_int), value :: signum
      character(kind=c_char), intent(out) :: name(*)
      integer(c_int), value :: length
    end subroutine c_signal_name
  end interface

contains

  !> Install the handlers; ok is false if one could not be installed.
  subroutine signal_install(ok)
    logical, intent(out) :: ok
    ok = c_signal_install() == 0
  end subroutine signal_install

  !> The number of the first handled signal received by this process, 0 if none.
  function signal_caught() result(signum)
    integer :: signum
    signum = int(c_signal_caught())
  end function signal_caught

  !> Name of a handled signal ('SIGUSR1', ...).
  function signal_name(signum) result(name)
    integer, intent(in) :: signum !< a number returned by signal_caught
    character(len=8) :: name
    character(kind=c_char) :: buffer(8)
    integer :: i
    call c_signal_name(int(signum, c_int), buffer, int(size(buffer), c_int))
    do i = 1, len(name)
      name(i:i) = buffer(i)
    end do
  end function signal_name

end module core_signal
