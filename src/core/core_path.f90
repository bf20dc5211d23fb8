!> File paths of the input: a path named in a deck is relative to the deck's
!> directory (absolute paths are taken as given), and messages name the full
!> path tried. The current directory comes from the C library (POSIX getcwd).
module core_path
  use, intrinsic :: iso_c_binding, only: c_char, c_size_t, c_ptr, c_associated, c_null_char
  implicit none
  private
  public :: path_from_deck, path_absolute, path_directory

  integer, parameter, public :: PATH_LEN = 256 !< a path as the deck gives it
  integer, parameter :: CWD_LEN = 4096

  interface
    !> char *getcwd(char *buf, size_t size)
    type(c_ptr) function c_getcwd(buf, size) bind(C, name='getcwd')
      import :: c_char, c_size_t, c_ptr
      character(kind=c_char), intent(out) :: buf(*)
      integer(c_size_t), value :: size
    end function c_getcwd
    !> char *realpath(const char *path, char *resolved_path), with a buffer of
    !> PATH_MAX (4096 on Linux) bytes.
    type(c_ptr) function c_realpath(path, resolved) bind(C, name='realpath')
      import :: c_char, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      character(kind=c_char), intent(out) :: resolved(*)
    end function c_realpath
  end interface

contains

  !> The path of file named in the deck at deck_path: file itself when it is
  !> absolute, else file in the deck's directory (its canonical path).
  function path_from_deck(deck_path, file) result(full)
    character(len=*), intent(in) :: deck_path !< the deck file as given on the command line
    character(len=*), intent(in) :: file !< a path from the deck
    character(len=:), allocatable :: full
    character(len=:), allocatable :: name
    name = trim(adjustl(file))
    if (len(name) > 0) then
      if (name(1:1) == '/') then
        full = name
        return
      end if
    end if
    full = path_absolute(path_directory(deck_path))//'/'//name
  end function path_from_deck

  !> The directory part of path ('.' when it has none; '/' for the root).
  function path_directory(path) result(dir)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: dir
    integer :: k
    k = index(trim(path), '/', back=.true.)
    if (k == 0) then
      dir = '.'
    else if (k == 1) then
      dir = '/'
    else
      dir = path(1:k - 1)
    end if
  end function path_directory

  !> path made absolute: the canonical path of an existing file or directory
  !> (POSIX realpath: symbolic links, '.' and '..' resolved); otherwise the
  !> path with the current directory before it, './' steps and repeated
  !> slashes removed.
  function path_absolute(path) result(full)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: full
    character(kind=c_char) :: buf(CWD_LEN)
    character(len=:), allocatable :: cwd
    integer :: k
    full = trim(path)
    if (len(full) == 0) return
    if (c_associated(c_realpath(full//c_null_char, buf))) then
      full = c_string(buf)
      return
    end if
    if (full(1:1) /= '/') then
      cwd = ''
      if (c_associated(c_getcwd(buf, int(CWD_LEN, c_size_t)))) cwd = c_string(buf)
      if (len(cwd) == 0) return
      full = cwd//'/'//full
    end if
    do
      k = index(full, '//')
      if (k == 0) exit
      full = full(1:k)//full(k + 2:)
    end do
    do
      k = index(full, '/./')
      if (k == 0) exit
      full = full(1:k)//full(k + 3:)
    end do
    if (len(full) > 2) then
      if (full(len(full) - 1:) == '/.') full = full(1:len(full) - 2)
    end if
  end function path_absolute

  !> The text of a NUL-terminated C string.
  function c_string(buf) result(text)
    character(kind=c_char), intent(in) :: buf(:)
    character(len=:), allocatable :: text
    integer :: k
    text = ''
    do k = 1, size(buf)
      if (buf(k) == c_null_char) exit
      text = text//buf(k)
    end do
  end function c_string

end module core_path
