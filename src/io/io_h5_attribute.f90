!> HDF5 attributes (scalars and fixed-length strings) on files, groups and
!> datasets; see io_h5 for the conventions (status and message, collective
!> writes).
module io_h5_attribute
  use, intrinsic :: iso_c_binding, only: c_ptr, c_loc, c_char, c_null_char
  use, intrinsic :: iso_fortran_env, only: int32, int64, real64
  use core_kinds, only: rk, i8
  use hdf5, only: hid_t, hsize_t, size_t, h5oopen_f, h5screate_f, &
    h5sget_simple_extent_npoints_f, H5S_SCALAR_F, h5dread_f, h5acreate_f, h5aopen_f, &
    h5aexists_f, h5adelete_f, h5awrite_f, h5aread_f, h5aget_space_f, h5aget_type_f, h5tcopy_f, &
    h5tset_size_f, h5tget_size_f, h5tset_strpad_f, h5tget_class_f, h5tis_variable_str_f, &
    H5T_C_S1, H5T_STR_NULLPAD_F, H5T_FLOAT_F, H5T_INTEGER_F, H5T_STRING_F, H5T_IEEE_F64LE, &
    H5T_STD_I32LE, h5kind_to_type, H5_REAL_KIND, H5_INTEGER_KIND
  use io_h5_base, only: IO_H5_OK, IO_H5_ERR_LIBRARY, IO_H5_ERR_ARGUMENT, IO_H5_ERR_NOT_FOUND, &
    IO_H5_ERR_MISMATCH, IO_H5_ERR_EXISTS, KIND_DATASET, KIND_SPACE, KIND_PLIST, &
    KIND_ATTRIBUTE, KIND_OBJECT, KIND_TYPE, KIND_GROUP, link_create_plist, release, check, &
    set_error, object_context, attribute_context, file_name_of, class_name, str, h5_path_exists
  implicit none
  private
  public :: h5_write_attr_real, h5_write_attr_int, h5_write_attr_string
  public :: h5_read_attr_real, h5_read_attr_int, h5_read_attr_string

contains

  !> Write (or replace) a scalar real(rk) attribute on a group, e.g. objpath '/'.
  !> Collective; every rank must pass the same value.
  subroutine h5_write_attr_real(file_id, objpath, name, value, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: objpath !< object carrying the attribute, e.g. '/'
    character(len=*), intent(in) :: name !< attribute name
    real(rk), intent(in), target :: value !< attribute value
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only

    call write_attribute(file_id, objpath, name, h5kind_to_type(real64, H5_REAL_KIND), &
        H5T_IEEE_F64LE, c_loc(value), status, message)
  end subroutine h5_write_attr_real

  !> Write (or replace) a scalar int32 attribute on a group, e.g. objpath '/'.
  !> Collective; every rank must pass the same value.
  subroutine h5_write_attr_int(file_id, objpath, name, value, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: objpath !< object carrying the attribute, e.g. '/'
    character(len=*), intent(in) :: name !< attribute name
    integer(int32), intent(in), target :: value !< attribute value
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only

    call write_attribute(file_id, objpath, name, h5kind_to_type(int32, H5_INTEGER_KIND), &
        H5T_STD_I32LE, c_loc(value), status, message)
  end subroutine h5_write_attr_int

  !> Write (or replace) a scalar fixed-length ASCII string attribute holding
  !> trim(value) (null-padded; h5py reads it as bytes). Collective; every rank must
  !> pass the same value.
  subroutine h5_write_attr_string(file_id, objpath, name, value, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: objpath !< object carrying the attribute, e.g. '/'
    character(len=*), intent(in) :: name !< attribute name
    character(len=*), intent(in) :: value !< attribute value; trailing blanks are dropped
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    character(kind=c_char, len=1), allocatable, target :: chars(:)
    integer(hid_t) :: string_type
    integer :: i, n
    character(len=:), allocatable :: context

    status = IO_H5_OK
    string_type = -1
    context = attribute_context(file_id, objpath, name)
    ! HDF5 strings cannot have length 0: an empty value is stored as one null byte.
    n = max(len_trim(value), 1)
    allocate(chars(n))
    chars = c_null_char
    do i = 1, len_trim(value)
      chars(i) = value(i:i)
    end do
    body: block
      call string_type_create(int(n, size_t), string_type, context, status, message)
      if (status /= IO_H5_OK) exit body
      call write_attribute(file_id, objpath, name, string_type, string_type, c_loc(chars), &
          status, message)
    end block body
    call release(KIND_TYPE, string_type, context, status, message)
  end subroutine h5_write_attr_string

  !> Read a scalar real attribute (any floating-point type in the file).
  subroutine h5_read_attr_real(file_id, objpath, name, value, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: objpath !< object carrying the attribute, e.g. '/'
    character(len=*), intent(in) :: name !< attribute name
    real(rk), intent(out), target :: value !< attribute value; 0 on failure
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only

    value = 0.0_rk
    call read_attribute(file_id, objpath, name, H5T_FLOAT_F, &
        h5kind_to_type(real64, H5_REAL_KIND), c_loc(value), status, message)
  end subroutine h5_read_attr_real

  !> Read a scalar integer attribute (any integer type in the file) into int32.
  subroutine h5_read_attr_int(file_id, objpath, name, value, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: objpath !< object carrying the attribute, e.g. '/'
    character(len=*), intent(in) :: name !< attribute name
    integer(int32), intent(out), target :: value !< attribute value; 0 on failure
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only

    value = 0
    call read_attribute(file_id, objpath, name, H5T_INTEGER_F, &
        h5kind_to_type(int32, H5_INTEGER_KIND), c_loc(value), status, message)
  end subroutine h5_read_attr_int

  !> Read a scalar fixed-length string attribute into value (blank-padded; the stored
  !> string ends at its first null byte). IO_H5_ERR_MISMATCH if it is longer than
  !> len(value) (value then holds the truncated text) or variable-length.
  subroutine h5_read_attr_string(file_id, objpath, name, value, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: objpath !< object carrying the attribute, e.g. '/'
    character(len=*), intent(in) :: name !< attribute name
    character(len=*), intent(out) :: value !< attribute text, blank-padded
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    character(kind=c_char, len=1), allocatable, target :: chars(:)
    integer(hid_t) :: obj, attr, space, file_type, mem_type
    integer(size_t) :: nchar
    integer :: hdferr, i, n
    logical :: is_variable
    type(c_ptr) :: address
    character(len=:), allocatable :: context

    status = IO_H5_OK
    value = ''
    attr = -1
    obj = -1
    space = -1
    file_type = -1
    mem_type = -1
    context = attribute_context(file_id, objpath, name)
    body: block
      call open_attribute(file_id, objpath, name, H5T_STRING_F, context, obj, attr, space, &
          file_type, status, message)
      if (status /= IO_H5_OK) exit body
      call h5tis_variable_str_f(file_type, is_variable, hdferr)
      call check(hdferr, 'h5tis_variable_str_f', context, status, message)
      if (status /= IO_H5_OK) exit body
      if (is_variable) then
        call set_error(IO_H5_ERR_MISMATCH, context // ' is a variable-length string; ' // &
            'only fixed-length strings are supported', status, message)
        exit body
      end if
      call h5tget_size_f(file_type, nchar, hdferr)
      call check(hdferr, 'h5tget_size_f', context, status, message)
      if (status /= IO_H5_OK) exit body
      call string_type_create(nchar, mem_type, context, status, message)
      if (status /= IO_H5_OK) exit body
      allocate(chars(max(int(nchar), 1)))
      chars = c_null_char
      address = c_loc(chars)
      call h5aread_f(attr, mem_type, address, hdferr)
      call check(hdferr, 'h5aread_f', context, status, message)
      if (status /= IO_H5_OK) exit body
      n = size(chars)
      do i = 1, size(chars)
        if (chars(i) == c_null_char) then
          n = i - 1
          exit
        end if
      end do
      do i = 1, min(n, len(value))
        value(i:i) = chars(i)
      end do
      if (n > len(value)) then
        call set_error(IO_H5_ERR_MISMATCH, context // ' has ' // str(n) // &
            ' characters but the buffer holds only ' // str(len(value)), status, message)
      end if
    end block body
    call release(KIND_TYPE, mem_type, context, status, message)
    call release(KIND_TYPE, file_type, context, status, message)
    call release(KIND_SPACE, space, context, status, message)
    call release(KIND_ATTRIBUTE, attr, context, status, message)
    call release(KIND_OBJECT, obj, context, status, message)
  end subroutine h5_read_attr_string

  ! ----------------------------------------------------------------- helpers

  !> Write (or replace) a scalar attribute on the object at objpath. Collective.
  subroutine write_attribute(file_id, objpath, name, mem_type, file_type, buffer, status, &
      message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: objpath !< object carrying the attribute
    character(len=*), intent(in) :: name !< attribute name
    integer(hid_t), intent(in) :: mem_type !< HDF5 type of the value in memory
    integer(hid_t), intent(in) :: file_type !< HDF5 type in the file
    type(c_ptr), intent(in) :: buffer !< address of the value
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(hid_t) :: obj, attr, space
    integer :: hdferr
    logical :: exists
    character(len=:), allocatable :: context

    status = IO_H5_OK
    obj = -1
    attr = -1
    space = -1
    context = attribute_context(file_id, objpath, name)
    body: block
      call open_object(file_id, objpath, context, obj, status, message)
      if (status /= IO_H5_OK) exit body
      call h5aexists_f(obj, name, exists, hdferr)
      call check(hdferr, 'h5aexists_f', context, status, message)
      if (status /= IO_H5_OK) exit body
      if (exists) then
        call h5adelete_f(obj, name, hdferr)
        call check(hdferr, 'h5adelete_f', context, status, message)
        if (status /= IO_H5_OK) exit body
      end if
      call h5screate_f(H5S_SCALAR_F, space, hdferr)
      call check(hdferr, 'h5screate_f', context, status, message)
      if (status /= IO_H5_OK) then
        space = -1
        exit body
      end if
      call h5acreate_f(obj, name, file_type, space, attr, hdferr)
      call check(hdferr, 'h5acreate_f', context, status, message)
      if (status /= IO_H5_OK) then
        attr = -1
        exit body
      end if
      call h5awrite_f(attr, mem_type, buffer, hdferr)
      call check(hdferr, 'h5awrite_f', context, status, message)
    end block body
    call release(KIND_ATTRIBUTE, attr, context, status, message)
    call release(KIND_SPACE, space, context, status, message)
    call release(KIND_OBJECT, obj, context, status, message)
  end subroutine write_attribute

  !> Read a scalar numeric attribute after checking that it exists, holds one value and
  !> has the expected type class.
  subroutine read_attribute(file_id, objpath, name, type_class, mem_type, buffer, status, &
      message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: objpath !< object carrying the attribute
    character(len=*), intent(in) :: name !< attribute name
    integer, intent(in) :: type_class !< expected type class
    integer(hid_t), intent(in) :: mem_type !< HDF5 type of the value in memory
    type(c_ptr), intent(in) :: buffer !< address of the value
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(hid_t) :: obj, attr, space, file_type
    integer :: hdferr
    type(c_ptr) :: address
    character(len=:), allocatable :: context

    status = IO_H5_OK
    ! Workaround: HDF5 1.10 h5aread_f/h5dread_f take the C_PTR buffer with intent(inout).
    address = buffer
    context = attribute_context(file_id, objpath, name)
    call open_attribute(file_id, objpath, name, type_class, context, obj, attr, space, &
        file_type, status, message)
    if (status == IO_H5_OK) then
      call h5aread_f(attr, mem_type, address, hdferr)
      call check(hdferr, 'h5aread_f', context, status, message)
    end if
    call release(KIND_TYPE, file_type, context, status, message)
    call release(KIND_SPACE, space, context, status, message)
    call release(KIND_ATTRIBUTE, attr, context, status, message)
    call release(KIND_OBJECT, obj, context, status, message)
  end subroutine read_attribute

  !> Open an attribute, its dataspace and its file type; check that it exists, holds
  !> exactly one value and has the expected type class. Ids not opened are -1.
  subroutine open_attribute(file_id, objpath, name, type_class, context, obj, attr, space, &
      file_type, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: objpath !< object carrying the attribute
    character(len=*), intent(in) :: name !< attribute name
    integer, intent(in) :: type_class !< expected type class
    character(len=*), intent(in) :: context !< description for messages
    integer(hid_t), intent(out) :: obj !< open object, or -1
    integer(hid_t), intent(out) :: attr !< open attribute, or -1
    integer(hid_t), intent(out) :: space !< its dataspace, or -1
    integer(hid_t), intent(out) :: file_type !< its type, or -1
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(hsize_t) :: npoints
    integer :: hdferr, file_class
    logical :: exists

    status = IO_H5_OK
    obj = -1
    attr = -1
    space = -1
    file_type = -1
    call open_object(file_id, objpath, context, obj, status, message)
    if (status /= IO_H5_OK) return
    call h5aexists_f(obj, name, exists, hdferr)
    call check(hdferr, 'h5aexists_f', context, status, message)
    if (status /= IO_H5_OK) return
    if (.not. exists) then
      call set_error(IO_H5_ERR_NOT_FOUND, context // ' does not exist', status, message)
      return
    end if
    call h5aopen_f(obj, name, attr, hdferr)
    call check(hdferr, 'h5aopen_f', context, status, message)
    if (hdferr < 0) then
      attr = -1
      return
    end if
    call h5aget_space_f(attr, space, hdferr)
    call check(hdferr, 'h5aget_space_f', context, status, message)
    if (hdferr < 0) then
      space = -1
      return
    end if
    call h5sget_simple_extent_npoints_f(space, npoints, hdferr)
    call check(hdferr, 'h5sget_simple_extent_npoints_f', context, status, message)
    if (hdferr < 0) return
    if (npoints /= 1) then
      call set_error(IO_H5_ERR_MISMATCH, context // ' holds ' // str(int(npoints, i8)) // &
          ' values; expected a scalar', status, message)
      return
    end if
    call h5aget_type_f(attr, file_type, hdferr)
    call check(hdferr, 'h5aget_type_f', context, status, message)
    if (hdferr < 0) then
      file_type = -1
      return
    end if
    call h5tget_class_f(file_type, file_class, hdferr)
    call check(hdferr, 'h5tget_class_f', context, status, message)
    if (hdferr < 0) return
    if (file_class /= type_class) then
      call set_error(IO_H5_ERR_MISMATCH, context // ' holds ' // class_name(file_class) // &
          ' data, expected ' // class_name(type_class), status, message)
    end if
  end subroutine open_attribute

  !> Open the object (group or dataset) at objpath, with a clear message if it is missing.
  subroutine open_object(file_id, objpath, context, obj, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: objpath !< object path, e.g. '/' or '/mesh'
    character(len=*), intent(in) :: context !< description for messages
    integer(hid_t), intent(out) :: obj !< open object, or -1
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer :: hdferr
    logical :: exists

    status = IO_H5_OK
    obj = -1
    call h5_path_exists(file_id, objpath, exists, status, message)
    if (status /= IO_H5_OK) return
    if (.not. exists) then
      call set_error(IO_H5_ERR_NOT_FOUND, context // ": object '" // trim(objpath) // &
          "' does not exist", status, message)
      return
    end if
    call h5oopen_f(file_id, objpath, obj, hdferr)
    call check(hdferr, 'h5oopen_f', context, status, message)
    if (hdferr < 0) obj = -1
  end subroutine open_object

  !> A fixed-length, null-padded ASCII string type of nchar characters.
  subroutine string_type_create(nchar, string_type, context, status, message)
    integer(size_t), intent(in) :: nchar !< length in bytes (>= 1)
    integer(hid_t), intent(out) :: string_type !< new type, or -1 on failure
    character(len=*), intent(in) :: context !< description for messages
    integer, intent(inout) :: status !< keeps an earlier error
    character(len=*), intent(inout) :: message !< set on a first failure only
    integer :: hdferr

    string_type = -1
    call h5tcopy_f(H5T_C_S1, string_type, hdferr)
    call check(hdferr, 'h5tcopy_f', context, status, message)
    if (hdferr < 0) then
      string_type = -1
      return
    end if
    call h5tset_size_f(string_type, max(nchar, 1_size_t), hdferr)
    call check(hdferr, 'h5tset_size_f', context, status, message)
    if (hdferr >= 0) then
      call h5tset_strpad_f(string_type, H5T_STR_NULLPAD_F, hdferr)
      call check(hdferr, 'h5tset_strpad_f', context, status, message)
    end if
    if (hdferr < 0) call release(KIND_TYPE, string_type, context, status, message)
  end subroutine string_type_create

end module io_h5_attribute
