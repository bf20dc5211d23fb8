!> This process's memory as the Linux kernel reports it.
module core_memory
  use core_kinds, only: rk
  implicit none
  private
  public :: peak_memory_mb

contains

  !> Peak resident set size (VmHWM of /proc/self/status) in MB (10^6 bytes);
  !> -1 where the file or the line is missing (not Linux).
  function peak_memory_mb() result(mb)
    real(rk) :: mb
    character(len=256) :: line
    integer :: unit, ios, kb
    mb = -1.0_rk
    open(newunit=unit, file='/proc/self/status', action='read', status='old', iostat=ios)
    if (ios /= 0) return
    do
      read(unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (line(1:6) == 'VmHWM:') then
        read(line(7:), *, iostat=ios) kb
        if (ios == 0) mb = real(kb, rk) * 1024.0_rk / 1.0e6_rk
        exit
      end if
    end do
    close(unit)
  end function peak_memory_mb

end module core_memory
