!> Unit test of io_h5: write a file collectively with an uneven row split (one rank
!> empty when there are 3 or more), read it back with another split and check every
!> value bit for bit; check the error paths (missing file, dataset, attribute; shape,
!> type and range mismatches). Run on 1, 2 or 3 ranks.
program test_io_h5
  use, intrinsic :: iso_fortran_env, only: int32, int64, output_unit
  use mpi_f08, only: MPI_Comm, MPI_COMM_WORLD, MPI_INFO_NULL, MPI_INTEGER, MPI_SUM, &
    MPI_Init, MPI_Finalize, MPI_Comm_rank, MPI_Comm_size, MPI_Allreduce, MPI_Barrier
  use core_kinds, only: rk, i8
  use io_h5, only: hid_t, IO_H5_OK, IO_H5_ERR_NOT_FOUND, IO_H5_ERR_MISMATCH, &
    IO_H5_ERR_EXISTS, IO_H5_ERR_ARGUMENT, &
    h5_library_open, h5_library_close, h5_create_file, h5_open_file, h5_close_file, &
    h5_create_group, h5_path_exists, h5_dataset_rows, &
    h5_write_real_rows, h5_write_real_vector, h5_write_int_rows, h5_write_int_vector, &
    h5_write_i8_vector, h5_read_real_rows, h5_read_real_vector, h5_read_int_rows, &
    h5_read_int_vector, h5_read_i8_vector, &
    h5_write_attr_real, h5_write_attr_int, h5_write_attr_string, &
    h5_read_attr_real, h5_read_attr_int, h5_read_attr_string
  implicit none

  character(len=*), parameter :: FILENAME = 'test_io_h5.h5'
  integer(i8), parameter :: NROW = 11 !< rows of the 2D datasets
  integer(i8), parameter :: NVEC = 7 !< entries of the 1D datasets
  integer, parameter :: NCOMP = 3
  integer, parameter :: NCORNER = 8
  character(len=*), parameter :: TITLE = 'impact3d io_h5 unit test'

  type(MPI_Comm) :: comm
  integer :: rank, nrank, npass, nfail, status, total(2)
  integer(hid_t) :: file_id
  character(len=512) :: message
  integer(i8) :: offset, nlocal, voffset, vlocal, nglobal
  integer :: ncomp_read, cycle_read
  logical :: exists
  real(rk) :: time_read, one_value(1)
  character(len=64) :: title_read
  character(len=4) :: short_text
  real(rk), allocatable :: coordinates(:, :), coordinates_read(:, :), density(:)
  real(rk), allocatable :: density_read(:), empty_real(:)
  integer(int32), allocatable :: connectivity(:, :), connectivity_read(:, :), block(:)
  integer(int32), allocatable :: block_read(:), four_corners(:, :)
  integer(int64), allocatable :: ids(:), ids_read(:)

  npass = 0
  nfail = 0
  call MPI_Init()
  comm = MPI_COMM_WORLD
  call MPI_Comm_rank(comm, rank)
  call MPI_Comm_size(comm, nrank)
  message = ''

  call h5_library_open(status, message)
  call check_status('library open', status)

  ! ---------------------------------------------------------------- write
  call split(NROW, nrank, rank, .false., offset, nlocal)
  call split(NVEC, nrank, rank, .false., voffset, vlocal)
  allocate(coordinates(NCOMP, nlocal), connectivity(NCORNER, nlocal))
  allocate(density(vlocal), block(vlocal), ids(vlocal))
  call fill_rows(offset, coordinates, connectivity)
  call fill_vectors(voffset, density, block, ids)
  allocate(empty_real(0))

  call h5_create_file(FILENAME, comm%MPI_VAL, MPI_INFO_NULL%MPI_VAL, file_id, status, message)
  call check_status('create file', status)
  call h5_create_group(file_id, '/mesh', status, message)
  call check_status('create group /mesh', status)
  call h5_create_group(file_id, '/mesh', status, message)
  call check_status('create existing group /mesh again', status)
  call h5_write_real_rows(file_id, '/mesh/coordinates', coordinates, NROW, offset, status, &
      message)
  call check_status('write real rows', status)
  call h5_write_int_rows(file_id, '/mesh/connectivity', connectivity, NROW, offset, &
      status, message)
  call check_status('write int rows', status)
  ! '/zones' is created on the fly as a missing parent.
  call h5_write_real_vector(file_id, '/zones/density', density, NVEC, voffset, status, &
      message)
  call check_status('write real vector', status)
  call h5_write_int_vector(file_id, '/mesh/block', block, NVEC, voffset, status, message)
  call check_status('write int vector', status)
  call h5_write_i8_vector(file_id, '/mesh/global_id', ids, NVEC, voffset, status, message)
  call check_status('write int64 vector', status)
  call h5_write_real_vector(file_id, '/zones/empty', empty_real, 0_i8, 0_i8, status, &
      message)
  call check_status('write zero-length vector', status)
  call h5_write_real_vector(file_id, '/zones/density', density, NVEC, voffset, status, &
      message)
  call check_code('write over an existing dataset fails', status, IO_H5_ERR_EXISTS)
  ! Rank 0 asks for rows beyond the end; the others still complete the collective write.
  if (rank == 0) then
    call h5_write_real_vector(file_id, '/zones/bad_range', density, NVEC, NVEC, status, &
        message)
    call check_code('write rows out of range fails', status, IO_H5_ERR_ARGUMENT)
  else
    call h5_write_real_vector(file_id, '/zones/bad_range', empty_real, NVEC, 0_i8, status, &
        message)
    call check_status('write beside an out-of-range rank', status)
  end if

  call h5_write_attr_real(file_id, '/', 'time', -1.0_rk, status, message)
  call check_status('write real attribute', status)
  call h5_write_attr_real(file_id, '/', 'time', 1.0_rk / 3.0_rk, status, message)
  call check_status('replace real attribute', status)
  call h5_write_attr_int(file_id, '/', 'cycle', 123456_int32, status, message)
  call check_status('write int attribute', status)
  call h5_write_attr_int(file_id, '/', 'format_version', 1_int32, status, message)
  call check_status('write int attribute 2', status)
  call h5_write_attr_string(file_id, '/', 'title', 'a longer title that gets replaced', &
      status, message)
  call check_status('write string attribute', status)
  call h5_write_attr_string(file_id, '/', 'title', TITLE, status, message)
  call check_status('replace string attribute', status)
  call h5_write_attr_string(file_id, '/', 'empty', '', status, message)
  call check_status('write empty string attribute', status)
  call h5_write_attr_string(file_id, '/mesh', 'units', 'cm g us', status, message)
  call check_status('write string attribute on a group', status)
  call h5_write_attr_int(file_id, '/nowhere', 'cycle', 1_int32, status, message)
  call check_code('write attribute on a missing object fails', status, IO_H5_ERR_NOT_FOUND)
  call h5_close_file(file_id, status, message)
  call check_status('close written file', status)
  call check_true('closed id is -1', file_id == -1)

  ! ----------------------------------------------------------------- read
  ! Read with another split (rank order reversed, a different rank empty).
  call split(NROW, nrank, rank, .true., offset, nlocal)
  call split(NVEC, nrank, rank, .true., voffset, vlocal)
  deallocate(coordinates, connectivity, density, block, ids)
  allocate(coordinates(NCOMP, nlocal), connectivity(NCORNER, nlocal))
  allocate(density(vlocal), block(vlocal), ids(vlocal))
  call fill_rows(offset, coordinates, connectivity)
  call fill_vectors(voffset, density, block, ids)
  allocate(coordinates_read(NCOMP, nlocal), connectivity_read(NCORNER, nlocal))
  allocate(density_read(vlocal), block_read(vlocal), ids_read(vlocal))
  coordinates_read = -7.0_rk
  connectivity_read = -7
  density_read = -7.0_rk
  block_read = -7
  ids_read = -7

  call h5_open_file(FILENAME, comm%MPI_VAL, MPI_INFO_NULL%MPI_VAL, file_id, status, message)
  call check_status('open file', status)

  call h5_dataset_rows(file_id, '/mesh/coordinates', nglobal, ncomp_read, status, message)
  call check_status('dataset rows of 2D real', status)
  call check_true('2D real dims', nglobal == NROW .and. ncomp_read == NCOMP)
  call h5_dataset_rows(file_id, '/mesh/connectivity', nglobal, ncomp_read, status, message)
  call check_true('2D int dims', status == IO_H5_OK .and. nglobal == NROW .and. &
      ncomp_read == NCORNER)
  call h5_dataset_rows(file_id, '/mesh/global_id', nglobal, ncomp_read, status, message)
  call check_true('1D int64 dims', status == IO_H5_OK .and. nglobal == NVEC .and. &
      ncomp_read == 1)
  call h5_dataset_rows(file_id, '/zones/empty', nglobal, ncomp_read, status, message)
  call check_true('zero-length dims', status == IO_H5_OK .and. nglobal == 0 .and. &
      ncomp_read == 1)

  call h5_read_real_rows(file_id, '/mesh/coordinates', coordinates_read, offset, status, &
      message)
  call check_status('read real rows', status)
  call check_true('real rows bit-exact', all(same_bits(coordinates_read, coordinates)))
  call h5_read_int_rows(file_id, '/mesh/connectivity', connectivity_read, offset, status, &
      message)
  call check_status('read int rows', status)
  call check_true('int rows exact', all(connectivity_read == connectivity))
  call h5_read_real_vector(file_id, '/zones/density', density_read, voffset, status, message)
  call check_status('read real vector', status)
  call check_true('real vector bit-exact', all(same_bits(density_read, density)))
  call h5_read_int_vector(file_id, '/mesh/block', block_read, voffset, status, message)
  call check_status('read int vector', status)
  call check_true('int vector exact', all(block_read == block))
  call h5_read_i8_vector(file_id, '/mesh/global_id', ids_read, voffset, status, message)
  call check_status('read int64 vector', status)
  call check_true('int64 vector exact', all(ids_read == ids))
  call h5_read_real_vector(file_id, '/zones/empty', empty_real, 0_i8, status, message)
  call check_status('read zero-length vector', status)

  call h5_read_attr_real(file_id, '/', 'time', time_read, status, message)
  call check_status('read real attribute', status)
  call check_true('real attribute bit-exact', same_bits(time_read, 1.0_rk / 3.0_rk))
  call h5_read_attr_int(file_id, '/', 'cycle', cycle_read, status, message)
  call check_status('read int attribute', status)
  call check_true('int attribute exact', cycle_read == 123456)
  call h5_read_attr_string(file_id, '/', 'title', title_read, status, message)
  call check_status('read string attribute', status)
  call check_true('string attribute exact', title_read == TITLE)
  call h5_read_attr_string(file_id, '/', 'empty', title_read, status, message)
  call check_true('empty string attribute', status == IO_H5_OK .and. title_read == '')
  call h5_read_attr_string(file_id, '/mesh', 'units', title_read, status, message)
  call check_true('string attribute on a group', status == IO_H5_OK .and. &
      title_read == 'cm g us')

  ! --------------------------------------------------------- error paths
  call h5_path_exists(file_id, '/nope/x', exists, status, message)
  call check_true('missing path does not exist', status == IO_H5_OK .and. .not. exists)
  call h5_path_exists(file_id, '/mesh/coordinates', exists, status, message)
  call check_true('existing path exists', status == IO_H5_OK .and. exists)
  message = ''
  call h5_read_real_rows(file_id, '/nope/x', coordinates_read, offset, status, message)
  call check_code('read missing dataset fails', status, IO_H5_ERR_NOT_FOUND)
  call check_true('missing dataset message names it', index(message, '/nope/x') > 0)
  call h5_dataset_rows(file_id, '/zones/pressure', nglobal, ncomp_read, status, message)
  call check_code('dims of missing dataset fail', status, IO_H5_ERR_NOT_FOUND)
  allocate(four_corners(4, nlocal))
  call h5_read_int_rows(file_id, '/mesh/connectivity', four_corners, offset, status, message)
  call check_code('read with wrong ncomp fails', status, IO_H5_ERR_MISMATCH)
  call h5_read_int_vector(file_id, '/zones/density', block_read, voffset, status, message)
  call check_code('read real dataset as int fails', status, IO_H5_ERR_MISMATCH)
  call h5_read_real_vector(file_id, '/mesh/coordinates', density_read, voffset, status, &
      message)
  call check_code('read 2D dataset as vector fails', status, IO_H5_ERR_MISMATCH)
  ! Only the last rank reads past the end; the others complete the collective read.
  if (rank == nrank - 1) then
    call h5_read_real_vector(file_id, '/zones/density', one_value, NVEC, status, &
        message)
    call check_code('read past the end fails', status, IO_H5_ERR_MISMATCH)
  else
    call h5_read_real_vector(file_id, '/zones/density', density_read, voffset, status, &
        message)
    call check_true('read beside an out-of-range rank', status == IO_H5_OK .and. &
        all(same_bits(density_read, density)))
  end if
  call h5_read_attr_int(file_id, '/', 'missing', cycle_read, status, message)
  call check_code('read missing attribute fails', status, IO_H5_ERR_NOT_FOUND)
  call h5_read_attr_int(file_id, '/', 'time', cycle_read, status, message)
  call check_code('read real attribute as int fails', status, IO_H5_ERR_MISMATCH)
  call h5_read_attr_string(file_id, '/', 'title', short_text, status, message)
  call check_code('read string into short buffer fails', status, IO_H5_ERR_MISMATCH)
  call check_true('short buffer holds the start', short_text == TITLE(1:4))

  call h5_close_file(file_id, status, message)
  call check_status('close read file', status)

  message = ''
  call h5_open_file('no_such_file.h5', comm%MPI_VAL, MPI_INFO_NULL%MPI_VAL, file_id, status, &
      message)
  call check_code('open missing file fails', status, IO_H5_ERR_NOT_FOUND)
  call check_true('missing file message names it', index(message, 'no_such_file.h5') > 0)
  call check_true('failed open gives id -1', file_id == -1)
  if (rank == 0) write(output_unit, '(a)') 'expected error: ' // trim(message)

  call h5_library_close(status, message)
  call check_status('library close', status)

  ! ------------------------------------------------------------- summary
  call MPI_Allreduce([npass, nfail], total, 2, MPI_INTEGER, MPI_SUM, comm)
  if (rank == 0) write(output_unit, '(i0, a, i0, a)') total(1), ' passed, ', total(2), &
      ' failed'
  call MPI_Barrier(comm)
  call MPI_Finalize()
  if (total(2) > 0) error stop 1

contains

  !> Rows [offset, offset + nlocal) of rank `me` in an uneven split of n rows: weights
  !> 1, 2, ..., with the last rank empty when there are 3 or more ranks; `reverse`
  !> hands the pieces out in reverse rank order.
  subroutine split(n, nparts, me, reverse, offset, nlocal)
    integer(i8), intent(in) :: n
    integer, intent(in) :: nparts, me
    logical, intent(in) :: reverse
    integer(i8), intent(out) :: offset, nlocal
    integer(i8) :: weight(0:nparts - 1), first(0:nparts)
    integer :: part, piece

    do part = 0, nparts - 1
      weight(part) = part + 1
    end do
    if (nparts >= 3) weight(nparts - 1) = 0
    first(0) = 0
    do part = 1, nparts
      first(part) = n * sum(weight(0:part - 1)) / sum(weight)
    end do
    piece = me
    if (reverse) piece = nparts - 1 - me
    offset = first(piece)
    nlocal = first(piece + 1) - first(piece)
  end subroutine split

  !> Reference rows for global rows offset, offset + 1, ...: awkward bit patterns.
  subroutine fill_rows(offset, coordinates, connectivity)
    integer(i8), intent(in) :: offset
    real(rk), intent(out) :: coordinates(:, :)
    integer(int32), intent(out) :: connectivity(:, :)
    integer :: i, c
    integer(i8) :: row

    do i = 1, size(coordinates, 2)
      row = offset + i - 1
      do c = 1, size(coordinates, 1)
        coordinates(c, i) = real(row + 1, rk) / 3.0_rk + real(c, rk) * 1.0e-7_rk
      end do
      if (row == 0) coordinates(1, i) = -0.0_rk
      if (row == 1) coordinates(2, i) = huge(1.0_rk)
      if (row == 2) coordinates(3, i) = tiny(1.0_rk)
      do c = 1, size(connectivity, 1)
        connectivity(c, i) = int(8 * row + c - 1, int32)
      end do
      if (row == 3) connectivity(1, i) = -huge(1_int32)
    end do
  end subroutine fill_rows

  !> Reference 1D data for global entries offset, offset + 1, ...
  subroutine fill_vectors(offset, density, block, ids)
    integer(i8), intent(in) :: offset
    real(rk), intent(out) :: density(:)
    integer(int32), intent(out) :: block(:)
    integer(int64), intent(out) :: ids(:)
    integer :: i
    integer(i8) :: row

    do i = 1, size(density)
      row = offset + i - 1
      density(i) = sqrt(real(row + 2, rk)) * 7.85_rk
      block(i) = int(7 * row - 3, int32)
      ids(i) = 2_int64**40 + 3_int64 * row
    end do
  end subroutine fill_vectors

  !> Bitwise equality of two reals (distinguishes -0 from +0).
  elemental function same_bits(a, b) result(same)
    real(rk), intent(in) :: a, b
    logical :: same

    same = transfer(a, 1_int64) == transfer(b, 1_int64)
  end function same_bits

  subroutine check_true(name, condition)
    character(len=*), intent(in) :: name
    logical, intent(in) :: condition

    if (condition) then
      npass = npass + 1
    else
      nfail = nfail + 1
      write(output_unit, '(a, i0, a)') 'rank ', rank, ': FAILED: ' // name
    end if
  end subroutine check_true

  subroutine check_status(name, code)
    character(len=*), intent(in) :: name
    integer, intent(in) :: code

    if (code /= IO_H5_OK) then
      write(output_unit, '(a, i0, a)') 'rank ', rank, ': ' // name // ': ' // trim(message)
    end if
    call check_true(name, code == IO_H5_OK)
  end subroutine check_status

  subroutine check_code(name, code, expected)
    character(len=*), intent(in) :: name
    integer, intent(in) :: code, expected

    if (code /= expected) then
      write(output_unit, '(a, i0, a, i0, a, i0, a)') 'rank ', rank, ': ' // name // &
          ': status ', code, ', expected ', expected, ': ' // trim(message)
    end if
    call check_true(name, code == expected .and. len_trim(message) > 0)
  end subroutine check_code

end program test_io_h5
