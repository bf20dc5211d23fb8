!> Thin, checked wrappers around the parallel HDF5 Fortran API (HDF5 1.10).
!>
!> Conventions:
!> - No MPI in this module: callers pass the communicator and the info object as
!>   default-integer handles (with mpi_f08: `comm%MPI_VAL`, `MPI_INFO_NULL%MPI_VAL`).
!> - Errors: every routine has `integer, intent(out) :: status` and
!>   `character(len=*), intent(inout) :: message`. On success status is IO_H5_OK (0)
!>   and message is left untouched; on failure status is one of the IO_H5_ERR_*
!>   codes and message says what failed, on which object and in which file.
!>   Every HDF5 return code is checked; nothing here stops the program.
!> - Rows: an array a(ncomp, nlocal) on each rank is one dataset with HDF5 dims
!>   (ncomp, nglobal) in Fortran order, which h5py shows as shape (nglobal, ncomp):
!>   one row per item. Each rank owns the rows [offset, offset + nlocal), with a
!>   0-based int64 offset; nlocal may be 0. A vector a(nlocal) gives shape (nglobal,).
!> - Collective calls: file create/open/close, group and dataset creation, every
!>   dataset read and write (transfer mode H5FD_MPIO_COLLECTIVE_F) and attribute
!>   writes must be made by all ranks of the file's communicator in the same order,
!>   with the same path, name, nglobal and ncomp (and, for attributes, the same
!>   value). A rank whose own arguments are wrong (offset or nlocal out of range,
!>   shape mismatch on read) still takes part in the collective transfer with an
!>   empty selection and returns status /= 0, so no other rank is left waiting;
!>   callers reduce the status over ranks.
!> - File datatypes are fixed little-endian standard types (IEEE F64LE, STD I32LE,
!>   STD I64LE) so a file is the same on every platform; memory types come from
!>   h5kind_to_type for the exact Fortran kinds (real64, int32, int64).
!> - Datasets and groups are created with their missing parent groups.
!>
!> This module holds the library, files, groups and datasets; attributes are in
!> io_h5_attribute and the shared error handling in io_h5_base, both re-exported
!> here so callers use io_h5 alone.
module io_h5
  use, intrinsic :: iso_c_binding, only: c_ptr, c_loc, c_char, c_null_char
  use, intrinsic :: iso_fortran_env, only: int32, int64, real64
  use core_kinds, only: rk, i8
  use io_h5_base, only: IO_H5_OK, IO_H5_ERR_LIBRARY, IO_H5_ERR_ARGUMENT, IO_H5_ERR_NOT_FOUND, &
    IO_H5_ERR_MISMATCH, IO_H5_ERR_EXISTS, KIND_DATASET, KIND_SPACE, KIND_PLIST, &
    KIND_ATTRIBUTE, KIND_OBJECT, KIND_TYPE, KIND_GROUP, link_create_plist, release, check, &
    set_error, object_context, attribute_context, file_name_of, class_name, str, h5_path_exists
  use io_h5_attribute, only: h5_write_attr_real, h5_write_attr_int, h5_write_attr_string, &
    h5_read_attr_real, h5_read_attr_int, h5_read_attr_string
  use hdf5, only: hid_t, hsize_t, h5open_f, h5close_f, h5fcreate_f, h5fopen_f, h5fclose_f, &
    h5fis_hdf5_f, H5F_ACC_TRUNC_F, H5F_ACC_RDONLY_F, h5pcreate_f, h5pset_fapl_mpio_f, &
    h5pset_dxpl_mpio_f, H5P_FILE_ACCESS_F, H5P_DATASET_XFER_F, H5FD_MPIO_COLLECTIVE_F, &
    h5gcreate_f, h5gopen_f, h5screate_simple_f, h5sselect_hyperslab_f, h5sselect_none_f, &
    h5sget_simple_extent_ndims_f, h5sget_simple_extent_dims_f, H5S_SELECT_SET_F, h5dcreate_f, &
    h5dopen_f, h5dget_space_f, h5dget_type_f, h5dwrite_f, h5dread_f, h5tget_class_f, &
    H5T_FLOAT_F, H5T_INTEGER_F, H5T_IEEE_F64LE, H5T_STD_I32LE, H5T_STD_I64LE, h5kind_to_type, &
    H5_REAL_KIND, H5_INTEGER_KIND
  implicit none
  private

  public :: hid_t
  public :: IO_H5_OK, IO_H5_ERR_LIBRARY, IO_H5_ERR_ARGUMENT, IO_H5_ERR_NOT_FOUND
  public :: IO_H5_ERR_MISMATCH, IO_H5_ERR_EXISTS
  public :: h5_library_open, h5_library_close
  public :: h5_create_file, h5_open_file, h5_close_file, h5_create_group
  public :: h5_path_exists, h5_dataset_rows
  public :: h5_write_real_rows, h5_write_real_vector, h5_write_int_rows, h5_write_int_vector
  public :: h5_write_i8_vector
  public :: h5_read_real_rows, h5_read_real_vector, h5_read_int_rows, h5_read_int_vector
  public :: h5_read_i8_vector
  public :: h5_write_attr_real, h5_write_attr_int, h5_write_attr_string
  public :: h5_read_attr_real, h5_read_attr_int, h5_read_attr_string

contains

  ! ------------------------------------------------------------------ library

  !> Initialise the HDF5 Fortran library (h5open_f); call once, before anything else.
  subroutine h5_library_open(status, message)
    integer, intent(out) :: status !< IO_H5_OK or IO_H5_ERR_LIBRARY
    character(len=*), intent(inout) :: message !< set on failure only
    integer :: hdferr

    status = IO_H5_OK
    call h5open_f(hdferr)
    call check(hdferr, 'h5open_f', 'initialising the HDF5 Fortran library', status, message)
  end subroutine h5_library_open

  !> Close the HDF5 Fortran library (h5close_f); call once, after every file is closed.
  subroutine h5_library_close(status, message)
    integer, intent(out) :: status !< IO_H5_OK or IO_H5_ERR_LIBRARY
    character(len=*), intent(inout) :: message !< set on failure only
    integer :: hdferr

    status = IO_H5_OK
    call h5close_f(hdferr)
    call check(hdferr, 'h5close_f', 'closing the HDF5 Fortran library', status, message)
  end subroutine h5_library_close

  ! -------------------------------------------------------------------- files

  !> Create (truncate) a file for parallel access by every rank of a communicator.
  !> Collective.
  subroutine h5_create_file(filename, comm_handle, info_handle, file_id, status, message)
    character(len=*), intent(in) :: filename !< path of the file to create or overwrite
    integer, intent(in) :: comm_handle !< MPI communicator handle (comm%MPI_VAL)
    integer, intent(in) :: info_handle !< MPI info handle (MPI_INFO_NULL%MPI_VAL)
    integer(hid_t), intent(out) :: file_id !< the open file; -1 on failure
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(hid_t) :: fapl
    integer :: hdferr
    character(len=:), allocatable :: context

    status = IO_H5_OK
    file_id = -1
    fapl = -1
    context = "creating file '" // trim(filename) // "'"
    body: block
      call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, hdferr)
      call check(hdferr, 'h5pcreate_f', context, status, message)
      if (status /= IO_H5_OK) exit body
      call h5pset_fapl_mpio_f(fapl, comm_handle, info_handle, hdferr)
      call check(hdferr, 'h5pset_fapl_mpio_f', context, status, message)
      if (status /= IO_H5_OK) exit body
      call h5fcreate_f(filename, H5F_ACC_TRUNC_F, file_id, hdferr, access_prp=fapl)
      call check(hdferr, 'h5fcreate_f', context // ' (is the directory there and writable?)', &
          status, message)
      if (status /= IO_H5_OK) file_id = -1
    end block body
    call release(KIND_PLIST, fapl, context, status, message)
  end subroutine h5_create_file

  !> Open an existing file read-only for parallel access by every rank of a communicator.
  !> Collective. A missing or non-HDF5 file gives IO_H5_ERR_NOT_FOUND naming the file.
  subroutine h5_open_file(filename, comm_handle, info_handle, file_id, status, message)
    character(len=*), intent(in) :: filename !< path of the file to open
    integer, intent(in) :: comm_handle !< MPI communicator handle (comm%MPI_VAL)
    integer, intent(in) :: info_handle !< MPI info handle (MPI_INFO_NULL%MPI_VAL)
    integer(hid_t), intent(out) :: file_id !< the open file; -1 on failure
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(hid_t) :: fapl
    integer :: hdferr
    logical :: exists, is_hdf5
    character(len=:), allocatable :: context

    status = IO_H5_OK
    file_id = -1
    fapl = -1
    context = "opening file '" // trim(filename) // "'"
    body: block
      inquire(file=filename, exist=exists)
      if (.not. exists) then
        call set_error(IO_H5_ERR_NOT_FOUND, "cannot open file '" // trim(filename) // &
            "': no such file", status, message)
        exit body
      end if
      call h5fis_hdf5_f(filename, is_hdf5, hdferr)
      if (hdferr < 0) then
        call set_error(IO_H5_ERR_NOT_FOUND, "cannot open file '" // trim(filename) // &
            "': it cannot be read (permissions?)", status, message)
        exit body
      end if
      if (.not. is_hdf5) then
        call set_error(IO_H5_ERR_NOT_FOUND, "cannot open file '" // trim(filename) // &
            "': it is not an HDF5 file", status, message)
        exit body
      end if
      call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, hdferr)
      call check(hdferr, 'h5pcreate_f', context, status, message)
      if (status /= IO_H5_OK) exit body
      call h5pset_fapl_mpio_f(fapl, comm_handle, info_handle, hdferr)
      call check(hdferr, 'h5pset_fapl_mpio_f', context, status, message)
      if (status /= IO_H5_OK) exit body
      call h5fopen_f(filename, H5F_ACC_RDONLY_F, file_id, hdferr, access_prp=fapl)
      call check(hdferr, 'h5fopen_f', context, status, message)
      if (status /= IO_H5_OK) file_id = -1
    end block body
    call release(KIND_PLIST, fapl, context, status, message)
  end subroutine h5_open_file

  !> Close a file opened by h5_create_file or h5_open_file; file_id becomes -1. Collective.
  subroutine h5_close_file(file_id, status, message)
    integer(hid_t), intent(inout) :: file_id !< the file; -1 on return
    integer, intent(out) :: status !< IO_H5_OK or IO_H5_ERR_LIBRARY
    character(len=*), intent(inout) :: message !< set on failure only
    integer :: hdferr
    character(len=:), allocatable :: context

    status = IO_H5_OK
    context = "closing file '" // file_name_of(file_id) // "'"
    call h5fclose_f(file_id, hdferr)
    call check(hdferr, 'h5fclose_f', context, status, message)
    file_id = -1
  end subroutine h5_close_file

  ! ----------------------------------------------------------------- groups

  !> Create a group (e.g. '/mesh'), with any missing parents. An existing group is not
  !> an error; an existing object of another kind is. Collective.
  subroutine h5_create_group(file_id, path, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute group path, e.g. '/mesh'
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(hid_t) :: group_id, lcpl
    integer :: hdferr
    logical :: exists
    character(len=:), allocatable :: context

    status = IO_H5_OK
    group_id = -1
    lcpl = -1
    context = object_context('group', file_id, path)
    body: block
      call h5_path_exists(file_id, path, exists, status, message)
      if (status /= IO_H5_OK) exit body
      if (exists) then
        call h5gopen_f(file_id, path, group_id, hdferr)
        if (hdferr < 0) then
          group_id = -1
          call set_error(IO_H5_ERR_EXISTS, context // ' exists and is not a group', &
              status, message)
        end if
        exit body
      end if
      call link_create_plist(lcpl, context, status, message)
      if (status /= IO_H5_OK) exit body
      call h5gcreate_f(file_id, path, group_id, hdferr, lcpl_id=lcpl)
      call check(hdferr, 'h5gcreate_f', context, status, message)
      if (status /= IO_H5_OK) group_id = -1
    end block body
    call release(KIND_GROUP, group_id, context, status, message)
    call release(KIND_PLIST, lcpl, context, status, message)
  end subroutine h5_create_group

  ! ---------------------------------------------------------------- datasets

  !> Global dims of a dataset: nglobal rows of ncomp components (ncomp = 1 for a 1D
  !> dataset). IO_H5_ERR_NOT_FOUND if it does not exist; IO_H5_ERR_MISMATCH if it is
  !> neither 1D nor 2D.
  subroutine h5_dataset_rows(file_id, path, nglobal, ncomp, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute dataset path
    integer(i8), intent(out) :: nglobal !< number of rows (items); 0 on failure
    integer, intent(out) :: ncomp !< components per row; 0 on failure
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(hid_t) :: dset, space
    integer :: ndims
    integer(hsize_t) :: dims(2)
    character(len=:), allocatable :: context

    status = IO_H5_OK
    nglobal = 0
    ncomp = 0
    dset = -1
    space = -1
    context = object_context('dataset', file_id, path)
    body: block
      call open_dataset(file_id, path, context, dset, space, ndims, dims, status, message)
      if (status /= IO_H5_OK) exit body
      if (ndims == 1) then
        nglobal = int(dims(1), i8)
        ncomp = 1
      else if (ndims == 2) then
        nglobal = int(dims(2), i8)
        ncomp = int(dims(1))
      else
        call set_error(IO_H5_ERR_MISMATCH, context // ' has rank ' // str(ndims) // &
            '; expected 1 or 2', status, message)
      end if
    end block body
    call release(KIND_SPACE, space, context, status, message)
    call release(KIND_DATASET, dset, context, status, message)
  end subroutine h5_dataset_rows

  !> Write real(rk) a(ncomp, nlocal) as rows [offset, offset + nlocal) of a new
  !> dataset of nglobal rows (h5py shape (nglobal, ncomp)). Collective.
  subroutine h5_write_real_rows(file_id, path, a, nglobal, offset, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute dataset path; must not exist yet
    real(rk), intent(in), contiguous, target :: a(:, :) !< this rank's rows, a(ncomp, nlocal)
    integer(i8), intent(in) :: nglobal !< total rows over all ranks
    integer(i8), intent(in) :: offset !< 0-based first global row of this rank
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    real(rk), target :: placeholder(1)

    placeholder = 0.0_rk
    if (size(a) > 0) then
      call write_dataset(file_id, path, 2, size(a, 1), size(a, 2, kind=i8), nglobal, offset, &
          h5kind_to_type(real64, H5_REAL_KIND), H5T_IEEE_F64LE, c_loc(a), status, message)
    else
      call write_dataset(file_id, path, 2, size(a, 1), size(a, 2, kind=i8), nglobal, offset, &
          h5kind_to_type(real64, H5_REAL_KIND), H5T_IEEE_F64LE, c_loc(placeholder), &
          status, message)
    end if
  end subroutine h5_write_real_rows

  !> Write real(rk) a(nlocal) as entries [offset, offset + nlocal) of a new 1D
  !> dataset of nglobal entries (h5py shape (nglobal,)). Collective.
  subroutine h5_write_real_vector(file_id, path, a, nglobal, offset, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute dataset path; must not exist yet
    real(rk), intent(in), contiguous, target :: a(:) !< this rank's entries
    integer(i8), intent(in) :: nglobal !< total entries over all ranks
    integer(i8), intent(in) :: offset !< 0-based first global entry of this rank
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    real(rk), target :: placeholder(1)

    placeholder = 0.0_rk
    if (size(a) > 0) then
      call write_dataset(file_id, path, 1, 1, size(a, kind=i8), nglobal, offset, &
          h5kind_to_type(real64, H5_REAL_KIND), H5T_IEEE_F64LE, c_loc(a), status, message)
    else
      call write_dataset(file_id, path, 1, 1, size(a, kind=i8), nglobal, offset, &
          h5kind_to_type(real64, H5_REAL_KIND), H5T_IEEE_F64LE, c_loc(placeholder), &
          status, message)
    end if
  end subroutine h5_write_real_vector

  !> Write int32 a(ncomp, nlocal) as rows [offset, offset + nlocal) of a new
  !> dataset of nglobal rows (h5py shape (nglobal, ncomp)). Collective.
  subroutine h5_write_int_rows(file_id, path, a, nglobal, offset, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute dataset path; must not exist yet
    integer(int32), intent(in), contiguous, target :: a(:, :) !< this rank's rows
    integer(i8), intent(in) :: nglobal !< total rows over all ranks
    integer(i8), intent(in) :: offset !< 0-based first global row of this rank
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(int32), target :: placeholder(1)

    placeholder = 0
    if (size(a) > 0) then
      call write_dataset(file_id, path, 2, size(a, 1), size(a, 2, kind=i8), nglobal, offset, &
          h5kind_to_type(int32, H5_INTEGER_KIND), H5T_STD_I32LE, c_loc(a), status, message)
    else
      call write_dataset(file_id, path, 2, size(a, 1), size(a, 2, kind=i8), nglobal, offset, &
          h5kind_to_type(int32, H5_INTEGER_KIND), H5T_STD_I32LE, c_loc(placeholder), &
          status, message)
    end if
  end subroutine h5_write_int_rows

  !> Write int32 a(nlocal) as entries [offset, offset + nlocal) of a new 1D
  !> dataset of nglobal entries (h5py shape (nglobal,)). Collective.
  subroutine h5_write_int_vector(file_id, path, a, nglobal, offset, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute dataset path; must not exist yet
    integer(int32), intent(in), contiguous, target :: a(:) !< this rank's entries
    integer(i8), intent(in) :: nglobal !< total entries over all ranks
    integer(i8), intent(in) :: offset !< 0-based first global entry of this rank
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(int32), target :: placeholder(1)

    placeholder = 0
    if (size(a) > 0) then
      call write_dataset(file_id, path, 1, 1, size(a, kind=i8), nglobal, offset, &
          h5kind_to_type(int32, H5_INTEGER_KIND), H5T_STD_I32LE, c_loc(a), status, message)
    else
      call write_dataset(file_id, path, 1, 1, size(a, kind=i8), nglobal, offset, &
          h5kind_to_type(int32, H5_INTEGER_KIND), H5T_STD_I32LE, c_loc(placeholder), &
          status, message)
    end if
  end subroutine h5_write_int_vector

  !> Write int64 a(nlocal) (e.g. global ids) as entries [offset, offset + nlocal) of a
  !> new 1D dataset of nglobal entries (h5py shape (nglobal,)). Collective.
  subroutine h5_write_i8_vector(file_id, path, a, nglobal, offset, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute dataset path; must not exist yet
    integer(i8), intent(in), contiguous, target :: a(:) !< this rank's entries
    integer(i8), intent(in) :: nglobal !< total entries over all ranks
    integer(i8), intent(in) :: offset !< 0-based first global entry of this rank
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(i8), target :: placeholder(1)

    placeholder = 0
    if (size(a) > 0) then
      call write_dataset(file_id, path, 1, 1, size(a, kind=i8), nglobal, offset, &
          h5kind_to_type(int64, H5_INTEGER_KIND), H5T_STD_I64LE, c_loc(a), status, message)
    else
      call write_dataset(file_id, path, 1, 1, size(a, kind=i8), nglobal, offset, &
          h5kind_to_type(int64, H5_INTEGER_KIND), H5T_STD_I64LE, c_loc(placeholder), &
          status, message)
    end if
  end subroutine h5_write_i8_vector

  !> Read this rank's rows [offset, offset + nlocal) of a 2D real dataset into
  !> a(ncomp, nlocal), allocated by the caller. The dataset must have ncomp = size(a, 1)
  !> components, a floating-point type, and at least offset + nlocal rows. Collective.
  subroutine h5_read_real_rows(file_id, path, a, offset, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute dataset path
    real(rk), intent(inout), contiguous, target :: a(:, :) !< this rank's rows
    integer(i8), intent(in) :: offset !< 0-based first global row of this rank
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    real(rk), target :: placeholder(1)

    if (size(a) > 0) then
      call read_dataset(file_id, path, 2, size(a, 1), size(a, 2, kind=i8), offset, &
          h5kind_to_type(real64, H5_REAL_KIND), H5T_FLOAT_F, c_loc(a), status, message)
    else
      call read_dataset(file_id, path, 2, size(a, 1), size(a, 2, kind=i8), offset, &
          h5kind_to_type(real64, H5_REAL_KIND), H5T_FLOAT_F, c_loc(placeholder), &
          status, message)
    end if
  end subroutine h5_read_real_rows

  !> Read this rank's entries [offset, offset + size(a)) of a 1D real dataset.
  !> Collective.
  subroutine h5_read_real_vector(file_id, path, a, offset, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute dataset path
    real(rk), intent(inout), contiguous, target :: a(:) !< this rank's entries
    integer(i8), intent(in) :: offset !< 0-based first global entry of this rank
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    real(rk), target :: placeholder(1)

    if (size(a) > 0) then
      call read_dataset(file_id, path, 1, 1, size(a, kind=i8), offset, &
          h5kind_to_type(real64, H5_REAL_KIND), H5T_FLOAT_F, c_loc(a), status, message)
    else
      call read_dataset(file_id, path, 1, 1, size(a, kind=i8), offset, &
          h5kind_to_type(real64, H5_REAL_KIND), H5T_FLOAT_F, c_loc(placeholder), &
          status, message)
    end if
  end subroutine h5_read_real_vector

  !> Read this rank's rows [offset, offset + nlocal) of a 2D integer dataset into
  !> int32 a(ncomp, nlocal). Collective.
  subroutine h5_read_int_rows(file_id, path, a, offset, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute dataset path
    integer(int32), intent(inout), contiguous, target :: a(:, :) !< this rank's rows
    integer(i8), intent(in) :: offset !< 0-based first global row of this rank
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(int32), target :: placeholder(1)

    if (size(a) > 0) then
      call read_dataset(file_id, path, 2, size(a, 1), size(a, 2, kind=i8), offset, &
          h5kind_to_type(int32, H5_INTEGER_KIND), H5T_INTEGER_F, c_loc(a), status, message)
    else
      call read_dataset(file_id, path, 2, size(a, 1), size(a, 2, kind=i8), offset, &
          h5kind_to_type(int32, H5_INTEGER_KIND), H5T_INTEGER_F, c_loc(placeholder), &
          status, message)
    end if
  end subroutine h5_read_int_rows

  !> Read this rank's entries [offset, offset + size(a)) of a 1D integer dataset into
  !> int32 a. Collective.
  subroutine h5_read_int_vector(file_id, path, a, offset, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute dataset path
    integer(int32), intent(inout), contiguous, target :: a(:) !< this rank's entries
    integer(i8), intent(in) :: offset !< 0-based first global entry of this rank
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(int32), target :: placeholder(1)

    if (size(a) > 0) then
      call read_dataset(file_id, path, 1, 1, size(a, kind=i8), offset, &
          h5kind_to_type(int32, H5_INTEGER_KIND), H5T_INTEGER_F, c_loc(a), status, message)
    else
      call read_dataset(file_id, path, 1, 1, size(a, kind=i8), offset, &
          h5kind_to_type(int32, H5_INTEGER_KIND), H5T_INTEGER_F, c_loc(placeholder), &
          status, message)
    end if
  end subroutine h5_read_int_vector

  !> Read this rank's entries [offset, offset + size(a)) of a 1D integer dataset into
  !> int64 a (e.g. global ids). Collective.
  subroutine h5_read_i8_vector(file_id, path, a, offset, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute dataset path
    integer(i8), intent(inout), contiguous, target :: a(:) !< this rank's entries
    integer(i8), intent(in) :: offset !< 0-based first global entry of this rank
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(i8), target :: placeholder(1)

    if (size(a) > 0) then
      call read_dataset(file_id, path, 1, 1, size(a, kind=i8), offset, &
          h5kind_to_type(int64, H5_INTEGER_KIND), H5T_INTEGER_F, c_loc(a), status, message)
    else
      call read_dataset(file_id, path, 1, 1, size(a, kind=i8), offset, &
          h5kind_to_type(int64, H5_INTEGER_KIND), H5T_INTEGER_F, c_loc(placeholder), &
          status, message)
    end if
  end subroutine h5_read_i8_vector

  ! ----------------------------------------------------------------- helpers

  !> Create a dataset and write this rank's rows collectively. Local argument errors
  !> still take part in the collective write with an empty selection.
  subroutine write_dataset(file_id, path, ndims, ncomp, nlocal, nglobal, offset, mem_type, &
      file_type, buffer, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute dataset path
    integer, intent(in) :: ndims !< 1 (vector) or 2 (rows)
    integer, intent(in) :: ncomp !< components per row (1 for a vector)
    integer(i8), intent(in) :: nlocal !< rows on this rank
    integer(i8), intent(in) :: nglobal !< rows over all ranks
    integer(i8), intent(in) :: offset !< 0-based first row of this rank
    integer(hid_t), intent(in) :: mem_type !< HDF5 type of the buffer
    integer(hid_t), intent(in) :: file_type !< HDF5 type in the file
    type(c_ptr), intent(in) :: buffer !< address of the data (any valid address if empty)
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(hid_t) :: file_space, mem_space, dset, lcpl, dxpl
    integer(hsize_t) :: file_dims(2)
    integer :: hdferr
    logical :: exists, select_rows
    character(len=:), allocatable :: context

    status = IO_H5_OK
    file_space = -1
    mem_space = -1
    dset = -1
    lcpl = -1
    dxpl = -1
    context = object_context('dataset', file_id, path)
    body: block
      ! Arguments that every rank shares: an error here is the same on all ranks.
      if (ncomp < 1 .or. nglobal < 0) then
        call set_error(IO_H5_ERR_ARGUMENT, 'writing ' // context // ': need ncomp >= 1 ' // &
            'and nglobal >= 0, got ncomp = ' // str(ncomp) // ', nglobal = ' // &
            str(nglobal), status, message)
        exit body
      end if
      call h5_path_exists(file_id, path, exists, status, message)
      if (status /= IO_H5_OK) exit body
      if (exists) then
        call set_error(IO_H5_ERR_EXISTS, 'cannot create ' // context // &
            ': it already exists', status, message)
        exit body
      end if
      ! This rank's rows: on error, still take part in the collective write.
      select_rows = .true.
      if (offset < 0 .or. nlocal < 0 .or. offset > nglobal - nlocal) then
        call set_error(IO_H5_ERR_ARGUMENT, 'writing ' // context // ': rows [' // &
            str(offset) // ', ' // str(offset + nlocal) // ') are outside [0, ' // &
            str(nglobal) // ')', status, message)
        select_rows = .false.
      end if
      if (nlocal == 0) select_rows = .false.

      file_dims = [int(ncomp, hsize_t), int(nglobal, hsize_t)]
      if (ndims == 1) file_dims(1) = int(nglobal, hsize_t)
      call h5screate_simple_f(ndims, file_dims(1:ndims), file_space, hdferr)
      call check(hdferr, 'h5screate_simple_f', context, status, message)
      if (hdferr < 0) exit body
      call link_create_plist(lcpl, context, status, message)
      if (lcpl < 0) exit body
      call h5dcreate_f(file_id, path, file_type, file_space, dset, hdferr, lcpl_id=lcpl)
      call check(hdferr, 'h5dcreate_f', context, status, message)
      if (hdferr < 0) then
        dset = -1
        exit body
      end if

      ! An empty dataset has no storage to transfer (nglobal is the same on all ranks).
      if (nglobal == 0) exit body
      call select_rows_of(ndims, ncomp, nlocal, offset, select_rows, file_space, mem_space, &
          context, status, message)
      if (mem_space < 0) exit body
      call collective_transfer_plist(dxpl, context, status, message)
      if (dxpl < 0) exit body
      call h5dwrite_f(dset, mem_type, buffer, hdferr, mem_space_id=mem_space, &
          file_space_id=file_space, xfer_prp=dxpl)
      call check(hdferr, 'h5dwrite_f', context, status, message)
    end block body
    call release(KIND_PLIST, dxpl, context, status, message)
    call release(KIND_SPACE, mem_space, context, status, message)
    call release(KIND_DATASET, dset, context, status, message)
    call release(KIND_PLIST, lcpl, context, status, message)
    call release(KIND_SPACE, file_space, context, status, message)
  end subroutine write_dataset

  !> Read this rank's rows of a dataset collectively, after checking its rank, number of
  !> components, type class and extent. A rank whose check fails still takes part in
  !> the collective read with an empty selection.
  subroutine read_dataset(file_id, path, ndims, ncomp, nlocal, offset, mem_type, &
      type_class, buffer, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute dataset path
    integer, intent(in) :: ndims !< expected rank: 1 (vector) or 2 (rows)
    integer, intent(in) :: ncomp !< expected components per row (1 for a vector)
    integer(i8), intent(in) :: nlocal !< rows to read on this rank
    integer(i8), intent(in) :: offset !< 0-based first row of this rank
    integer(hid_t), intent(in) :: mem_type !< HDF5 type of the buffer
    integer, intent(in) :: type_class !< expected type class (H5T_FLOAT_F, H5T_INTEGER_F)
    type(c_ptr), intent(in) :: buffer !< address of the data (any valid address if empty)
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(hid_t) :: file_space, mem_space, dset, dxpl, file_type
    integer(hsize_t) :: dims(2)
    integer(i8) :: nglobal
    integer :: hdferr, file_ndims, file_class
    logical :: select_rows
    type(c_ptr) :: address
    character(len=:), allocatable :: context

    status = IO_H5_OK
    ! Workaround: HDF5 1.10 h5dread_f takes the C_PTR buffer with intent(inout).
    address = buffer
    file_space = -1
    mem_space = -1
    dset = -1
    dxpl = -1
    file_type = -1
    context = object_context('dataset', file_id, path)
    body: block
      call open_dataset(file_id, path, context, dset, file_space, file_ndims, dims, status, &
          message)
      if (status /= IO_H5_OK) exit body
      call h5dget_type_f(dset, file_type, hdferr)
      call check(hdferr, 'h5dget_type_f', context, status, message)
      if (hdferr < 0) then
        file_type = -1
        exit body
      end if
      call h5tget_class_f(file_type, file_class, hdferr)
      call check(hdferr, 'h5tget_class_f', context, status, message)
      if (hdferr < 0) exit body

      ! Checks of the file against this rank's request: on error, still take part in
      ! the collective read with nothing selected.
      select_rows = nlocal > 0
      nglobal = 0
      if (file_ndims /= ndims) then
        call set_error(IO_H5_ERR_MISMATCH, 'reading ' // context // ': it has rank ' // &
            str(file_ndims) // ', expected ' // str(ndims), status, message)
        select_rows = .false.
      else if (ndims == 2 .and. dims(1) /= int(ncomp, hsize_t)) then
        call set_error(IO_H5_ERR_MISMATCH, 'reading ' // context // ': it has ' // &
            str(int(dims(1), i8)) // ' components per row, expected ' // str(ncomp), &
            status, message)
        select_rows = .false.
      else if (file_class /= type_class) then
        call set_error(IO_H5_ERR_MISMATCH, 'reading ' // context // ': it holds ' // &
            class_name(file_class) // ' data, expected ' // class_name(type_class), &
            status, message)
        select_rows = .false.
      else
        nglobal = int(dims(ndims), i8)
        if (offset < 0 .or. nlocal < 0 .or. offset > nglobal - nlocal) then
          call set_error(IO_H5_ERR_MISMATCH, 'reading ' // context // ': rows [' // &
              str(offset) // ', ' // str(offset + nlocal) // ') are outside [0, ' // &
              str(nglobal) // ')', status, message)
          select_rows = .false.
        end if
      end if

      ! An empty dataset has no storage to transfer (and the same nglobal on all ranks).
      if (file_ndims == ndims .and. dims(file_ndims) == 0) exit body
      call select_rows_of(ndims, ncomp, nlocal, offset, select_rows, file_space, mem_space, &
          context, status, message)
      if (mem_space < 0) exit body
      call collective_transfer_plist(dxpl, context, status, message)
      if (dxpl < 0) exit body
      call h5dread_f(dset, mem_type, address, hdferr, mem_space_id=mem_space, &
          file_space_id=file_space, xfer_prp=dxpl)
      call check(hdferr, 'h5dread_f', context, status, message)
    end block body
    call release(KIND_PLIST, dxpl, context, status, message)
    call release(KIND_SPACE, mem_space, context, status, message)
    call release(KIND_TYPE, file_type, context, status, message)
    call release(KIND_SPACE, file_space, context, status, message)
    call release(KIND_DATASET, dset, context, status, message)
  end subroutine read_dataset

  !> Open an existing dataset and its file dataspace; report a missing dataset clearly.
  subroutine open_dataset(file_id, path, context, dset, space, ndims, dims, status, message)
    integer(hid_t), intent(in) :: file_id !< open file
    character(len=*), intent(in) :: path !< absolute dataset path
    character(len=*), intent(in) :: context !< description for messages
    integer(hid_t), intent(out) :: dset !< open dataset, or -1
    integer(hid_t), intent(out) :: space !< its dataspace, or -1
    integer, intent(out) :: ndims !< its rank (0 for a scalar)
    integer(hsize_t), intent(out) :: dims(2) !< its dims in Fortran order (first ndims)
    integer, intent(out) :: status !< IO_H5_OK or an IO_H5_ERR_* code
    character(len=*), intent(inout) :: message !< set on failure only
    integer(hsize_t) :: maxdims(2)
    integer :: hdferr
    logical :: exists

    status = IO_H5_OK
    dset = -1
    space = -1
    ndims = 0
    dims = 0
    call h5_path_exists(file_id, path, exists, status, message)
    if (status /= IO_H5_OK) return
    if (.not. exists) then
      call set_error(IO_H5_ERR_NOT_FOUND, context // ' does not exist', status, message)
      return
    end if
    call h5dopen_f(file_id, path, dset, hdferr)
    call check(hdferr, 'h5dopen_f', context // ' (is it a dataset?)', status, message)
    if (hdferr < 0) then
      dset = -1
      return
    end if
    call h5dget_space_f(dset, space, hdferr)
    call check(hdferr, 'h5dget_space_f', context, status, message)
    if (hdferr < 0) then
      space = -1
      return
    end if
    call h5sget_simple_extent_ndims_f(space, ndims, hdferr)
    call check(hdferr, 'h5sget_simple_extent_ndims_f', context, status, message)
    if (hdferr < 0) return
    if (ndims < 1 .or. ndims > 2) then
      call set_error(IO_H5_ERR_MISMATCH, context // ' has rank ' // str(ndims) // &
          '; expected 1 or 2', status, message)
      return
    end if
    ! h5sget_simple_extent_dims_f returns the rank in hdferr on success, -1 on failure.
    call h5sget_simple_extent_dims_f(space, dims(1:ndims), maxdims(1:ndims), hdferr)
    if (hdferr < 0) call check(hdferr, 'h5sget_simple_extent_dims_f', context, status, &
        message)
  end subroutine open_dataset

  !> Select this rank's rows [offset, offset + nlocal) in the file dataspace and make the
  !> matching memory dataspace; with select_rows false both selections are empty.
  subroutine select_rows_of(ndims, ncomp, nlocal, offset, select_rows, file_space, &
      mem_space, context, status, message)
    integer, intent(in) :: ndims !< 1 or 2
    integer, intent(in) :: ncomp !< components per row
    integer(i8), intent(in) :: nlocal !< rows on this rank
    integer(i8), intent(in) :: offset !< 0-based first row
    logical, intent(in) :: select_rows !< .false.: select nothing
    integer(hid_t), intent(in) :: file_space !< file dataspace to select in
    integer(hid_t), intent(out) :: mem_space !< new memory dataspace, or -1 on failure
    character(len=*), intent(in) :: context !< description for messages
    integer, intent(inout) :: status !< keeps an earlier error
    character(len=*), intent(inout) :: message !< set on a first failure only
    integer(hsize_t) :: start(2), counts(2)
    integer :: hdferr

    mem_space = -1
    if (select_rows) then
      start = [0_hsize_t, int(offset, hsize_t)]
      counts = [int(ncomp, hsize_t), int(nlocal, hsize_t)]
      if (ndims == 1) then
        start(1) = int(offset, hsize_t)
        counts(1) = int(nlocal, hsize_t)
      end if
      call h5sselect_hyperslab_f(file_space, H5S_SELECT_SET_F, start(1:ndims), &
          counts(1:ndims), hdferr)
      call check(hdferr, 'h5sselect_hyperslab_f', context, status, message)
      if (hdferr < 0) return
      call h5screate_simple_f(ndims, counts(1:ndims), mem_space, hdferr)
      call check(hdferr, 'h5screate_simple_f', context, status, message)
      if (hdferr < 0) mem_space = -1
    else
      call h5sselect_none_f(file_space, hdferr)
      call check(hdferr, 'h5sselect_none_f', context, status, message)
      if (hdferr < 0) return
      counts = 1
      call h5screate_simple_f(ndims, counts(1:ndims), mem_space, hdferr)
      call check(hdferr, 'h5screate_simple_f', context, status, message)
      if (hdferr < 0) then
        mem_space = -1
        return
      end if
      call h5sselect_none_f(mem_space, hdferr)
      call check(hdferr, 'h5sselect_none_f', context, status, message)
      if (hdferr < 0) call release(KIND_SPACE, mem_space, context, status, message)
    end if
  end subroutine select_rows_of

  !> Dataset transfer property list with collective MPI-IO.
  subroutine collective_transfer_plist(dxpl, context, status, message)
    integer(hid_t), intent(out) :: dxpl !< new property list, or -1 on failure
    character(len=*), intent(in) :: context !< description for messages
    integer, intent(inout) :: status !< keeps an earlier error
    character(len=*), intent(inout) :: message !< set on a first failure only
    integer :: hdferr

    call h5pcreate_f(H5P_DATASET_XFER_F, dxpl, hdferr)
    call check(hdferr, 'h5pcreate_f', context, status, message)
    if (hdferr < 0) then
      dxpl = -1
      return
    end if
    call h5pset_dxpl_mpio_f(dxpl, H5FD_MPIO_COLLECTIVE_F, hdferr)
    call check(hdferr, 'h5pset_dxpl_mpio_f', context, status, message)
    if (hdferr < 0) call release(KIND_PLIST, dxpl, context, status, message)
  end subroutine collective_transfer_plist

end module io_h5
