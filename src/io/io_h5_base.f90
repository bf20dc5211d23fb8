!> Shared pieces of the HDF5 wrappers (io_h5, io_h5_attribute): status codes,
!> error reporting, handle release, the names used in messages and
!> h5_path_exists. See io_h5 for the conventions.
module io_h5_base
  use, intrinsic :: iso_c_binding, only: c_ptr, c_loc, c_char, c_null_char
  use, intrinsic :: iso_fortran_env, only: int32, int64, real64
  use core_kinds, only: rk, i8
  use hdf5, only: hid_t, size_t, h5fget_name_f, h5pcreate_f, h5pclose_f, &
    h5pset_create_inter_group_f, H5P_LINK_CREATE_F, h5gclose_f, h5lexists_f, h5oclose_f, &
    h5sclose_f, h5dclose_f, h5aclose_f, h5tclose_f, H5T_FLOAT_F, H5T_INTEGER_F, H5T_STRING_F
  implicit none
  private
  public :: IO_H5_OK, IO_H5_ERR_LIBRARY, IO_H5_ERR_ARGUMENT, IO_H5_ERR_NOT_FOUND
  public :: IO_H5_ERR_MISMATCH, IO_H5_ERR_EXISTS
  public :: KIND_DATASET, KIND_SPACE, KIND_PLIST, KIND_ATTRIBUTE, KIND_OBJECT, KIND_TYPE
  public :: KIND_GROUP
  public :: link_create_plist, release, check, set_error, object_context, attribute_context
  public :: file_name_of, class_name, str, h5_path_exists

  !> Success.
  integer, parameter :: IO_H5_OK = 0
  !> An HDF5 library call failed.
  integer, parameter :: IO_H5_ERR_LIBRARY = 1
  !> An argument is invalid (negative offset, rows out of range, bad path, ...).
  integer, parameter :: IO_H5_ERR_ARGUMENT = 2
  !> A file, group, dataset or attribute does not exist.
  integer, parameter :: IO_H5_ERR_NOT_FOUND = 3
  !> A dataset or attribute has another rank, shape, type class or length than asked for.
  integer, parameter :: IO_H5_ERR_MISMATCH = 4
  !> A dataset to be created already exists.
  integer, parameter :: IO_H5_ERR_EXISTS = 5

  !> Object kinds for release().
  integer, parameter :: KIND_DATASET = 1, KIND_SPACE = 2, KIND_PLIST = 3, KIND_ATTRIBUTE = 4
  integer, parameter :: KIND_OBJECT = 5, KIND_TYPE = 6, KIND_GROUP = 7

contains

  !> Link creation property list that also creates missing parent groups.
  subroutine link_create_plist(lcpl, context, status, message)
    integer(hid_t), intent(out) :: lcpl !< new property list, or -1 on failure
    character(len=*), intent(in) :: context !< description for messages
    integer, intent(inout) :: status !< keeps an earlier error
    character(len=*), intent(inout) :: message !< set on a first failure only
    integer :: hdferr

    call h5pcreate_f(H5P_LINK_CREATE_F, lcpl, hdferr)
    call check(hdferr, 'h5pcreate_f', context, status, message)
    if (hdferr < 0) then
      lcpl = -1
      return
    end if
    call h5pset_create_inter_group_f(lcpl, 1, hdferr)
    call check(hdferr, 'h5pset_create_inter_group_f', context, status, message)
    if (hdferr < 0) call release(KIND_PLIST, lcpl, context, status, message)
  end subroutine link_create_plist

  !> Close an HDF5 id of the given kind if it is open (>= 0), and set it to -1.
  subroutine release(id_kind, id, context, status, message)
    integer, intent(in) :: id_kind !< one of the KIND_* constants
    integer(hid_t), intent(inout) :: id !< id to close; -1 on return
    character(len=*), intent(in) :: context !< description for messages
    integer, intent(inout) :: status !< keeps an earlier error
    character(len=*), intent(inout) :: message !< set on a first failure only
    integer :: hdferr

    if (id < 0) return
    select case (id_kind)
    case (KIND_DATASET)
      call h5dclose_f(id, hdferr)
      call check(hdferr, 'h5dclose_f', context, status, message)
    case (KIND_SPACE)
      call h5sclose_f(id, hdferr)
      call check(hdferr, 'h5sclose_f', context, status, message)
    case (KIND_PLIST)
      call h5pclose_f(id, hdferr)
      call check(hdferr, 'h5pclose_f', context, status, message)
    case (KIND_ATTRIBUTE)
      call h5aclose_f(id, hdferr)
      call check(hdferr, 'h5aclose_f', context, status, message)
    case (KIND_OBJECT)
      call h5oclose_f(id, hdferr)
      call check(hdferr, 'h5oclose_f', context, status, message)
    case (KIND_TYPE)
      call h5tclose_f(id, hdferr)
      call check(hdferr, 'h5tclose_f', context, status, message)
    case (KIND_GROUP)
      call h5gclose_f(id, hdferr)
      call check(hdferr, 'h5gclose_f', context, status, message)
    end select
    id = -1
  end subroutine release

  !> Turn a failed HDF5 return code (< 0) into an IO_H5_ERR_LIBRARY status, unless an
  !> earlier error is already recorded.
  subroutine check(hdferr, routine, context, status, message)
    integer, intent(in) :: hdferr !< HDF5 return code
    character(len=*), intent(in) :: routine !< name of the HDF5 routine called
    character(len=*), intent(in) :: context !< what was being done, to which object
    integer, intent(inout) :: status !< keeps an earlier error
    character(len=*), intent(inout) :: message !< set on a first failure only

    if (hdferr >= 0) return
    call set_error(IO_H5_ERR_LIBRARY, routine // ' failed: ' // context, status, message)
  end subroutine check

  !> Record an error unless one is already recorded (the first error is the cause).
  subroutine set_error(code, text, status, message)
    integer, intent(in) :: code !< IO_H5_ERR_* code
    character(len=*), intent(in) :: text !< what is wrong and where
    integer, intent(inout) :: status !< keeps an earlier error
    character(len=*), intent(inout) :: message !< set on a first failure only

    if (status /= IO_H5_OK) return
    status = code
    message = 'io_h5: ' // text
  end subroutine set_error

  !> "dataset '/a/b' in file 'x.h5'" for messages.
  function object_context(what, file_id, path) result(text)
    character(len=*), intent(in) :: what !< kind of object, e.g. 'dataset'
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< object path
    character(len=:), allocatable :: text

    text = what // " '" // trim(path) // "' in file '" // file_name_of(file_id) // "'"
  end function object_context

  !> "attribute 'time' of '/' in file 'x.h5'" for messages.
  function attribute_context(file_id, objpath, name) result(text)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: objpath !< object path
    character(len=*), intent(in) :: name !< attribute name
    character(len=:), allocatable :: text

    text = "attribute '" // trim(name) // "' of '" // trim(objpath) // "' in file '" // &
        file_name_of(file_id) // "'"
  end function attribute_context

  !> Name of the file that holds an object, or '?' if HDF5 cannot tell.
  function file_name_of(obj_id) result(name)
    integer(hid_t), intent(in) :: obj_id !< any id in the file
    character(len=:), allocatable :: name
    character(len=1024) :: buffer
    integer(size_t) :: length
    integer :: hdferr

    buffer = ''
    length = 0
    hdferr = -1
    if (obj_id >= 0) call h5fget_name_f(obj_id, buffer, length, hdferr)
    if (hdferr < 0) then
      name = '?'
    else
      name = trim(buffer(1:min(int(length), len(buffer))))
    end if
  end function file_name_of

  !> Name of an HDF5 type class for messages.
  function class_name(type_class) result(text)
    integer, intent(in) :: type_class !< HDF5 type class
    character(len=:), allocatable :: text

    if (type_class == H5T_FLOAT_F) then
      text = 'floating-point'
    else if (type_class == H5T_INTEGER_F) then
      text = 'integer'
    else if (type_class == H5T_STRING_F) then
      text = 'string'
    else
      text = 'class-' // str(type_class)
    end if
  end function class_name

  !> Decimal text of an integer (default or int64).
  function str(n) result(text)
    class(*), intent(in) :: n !< integer(int32) or integer(int64)
    character(len=:), allocatable :: text
    character(len=24) :: buffer

    select type (n)
    type is (integer(int32))
      write(buffer, '(i0)') n
    type is (integer(int64))
      write(buffer, '(i0)') n
    class default
      buffer = '?'
    end select
    text = trim(buffer)
  end function str

  !> Whether a link (group, dataset) exists at an absolute path, checking every
  !> component so that a missing parent gives .false. rather than an error.
  subroutine h5_path_exists(file_id, path, exists, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute path, e.g. '/mesh/coordinates'
    logical, intent(out) :: exists !< .true. if every component of path exists
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer :: i, last, hdferr

    status = IO_H5_OK
    exists = .false.
    last = len_trim(path)
    do while (last > 1)
      if (path(last:last) /= '/') exit
      last = last - 1
    end do
    if (last == 0) then
      call set_error(IO_H5_ERR_ARGUMENT, 'empty HDF5 path', status, message)
      return
    end if
    if (path(1:last) == '/') then
      exists = .true.
      return
    end if
    do i = 2, last
      if (i < last .and. path(i:i) /= '/') cycle
      if (i < last) then
        if (path(i - 1:i - 1) == '/') cycle
        call h5lexists_f(file_id, path(1:i - 1), exists, hdferr)
      else
        call h5lexists_f(file_id, path(1:last), exists, hdferr)
      end if
      if (hdferr < 0) then
        exists = .false.
        call set_error(IO_H5_ERR_ARGUMENT, "cannot resolve path '" // path(1:i) // &
            "' in file '" // file_name_of(file_id) // "' (a parent is not a group?)", &
            status, message)
        return
      end if
      if (.not. exists) return
    end do
  end subroutine h5_path_exists

end module io_h5_base
