!> Ending the process with an exit status and nothing printed (a STOP with a
!> code prints 'STOP n'; a variable code and quiet= are Fortran 2018).
module core_exit
  use, intrinsic :: iso_c_binding, only: c_int
  implicit none
  private
  public :: process_exit

  interface
    !> C exit(): the Fortran run-time library closes (flushes) its units at exit.
    subroutine c_exit(status) bind(C, name='exit')
      import :: c_int
      integer(c_int), value :: status
    end subroutine c_exit
  end interface

contains

  !> End the process with exit status code (MPI must be finalized already).
  subroutine process_exit(code)
    integer, intent(in) :: code
    call c_exit(int(code, c_int))
  end subroutine process_exit

end module core_exit
