!> The MPI environment: start-up, shutdown, abort, broadcasts and reductions.
!> The only module globals of the code live here: the communicator, rank and size.
module parallel_env
  use mpi_f08
  use core_kinds, only: rk, ik, i8
  use core_exact_sum, only: exact_sum_t, exact_pack, exact_unpack, EXACT_PACKED
  use, intrinsic :: iso_fortran_env, only: error_unit
  implicit none
  private
  public :: par_init, par_finalize, par_abort
  public :: par_rank, par_size, par_comm, par_comm_handle, par_info_null_handle, par_io_info_handle
  public :: par_bcast, par_sum, par_sum_array, par_min, par_max, par_max_array, par_allgather
  public :: par_sum_exact, traffic_count, par_sum_in_place

  !> Counters of one caller's communication (the contact's), for its run
  !> report: what this rank sent to other ranks and how often it had to
  !> meet them. The helpers that take an optional traffic argument add to
  !> it; nothing is counted on one rank.
  type, public :: traffic_t
    integer(i8) :: bytes = 0 !< payload bytes sent to other ranks, point to point
    integer(i8) :: messages = 0 !< point-to-point messages sent to other ranks
    integer(i8) :: collectives = 0 !< collective calls (reductions, all-to-alls, gathers)
    !> point-to-point exchanges in which this rank sent or received a message
    integer(i8) :: exchanges = 0
    real(rk) :: wait_seconds = 0.0_rk !< time in the blocking calls: waiting and transfer
  end type traffic_t

  type(MPI_Comm) :: comm_world !< the run's communicator (set once)
  type(MPI_Info) :: io_info = MPI_INFO_NULL !< MPI-IO hints of the dumps (set once)
  integer :: my_rank = 0 !< this rank
  integer :: n_ranks = 1 !< number of ranks

  !> Broadcast from rank 0.
  interface par_bcast
    module procedure bcast_int, bcast_int_array, bcast_i8_array, bcast_real, bcast_real_array, &
        bcast_real_array2, bcast_logical, bcast_logical_array, bcast_string, bcast_string_array
  end interface par_bcast

  !> Global sum (diagnostics only: the order is the MPI library's).
  interface par_sum
    module procedure sum_real, sum_int, sum_i8
  end interface par_sum

  !> Global minimum.
  interface par_min
    module procedure min_real, min_int
  end interface par_min

  !> Global maximum.
  interface par_max
    module procedure max_real, max_int
  end interface par_max

  !> Gather one small record from every rank onto every rank.
  interface par_allgather
    module procedure allgather_real, allgather_int, allgather_i8
  end interface par_allgather

contains

  !> Start MPI and record rank and size. PT-Scotch (parallel_partition)
  !> communicates from threads of its own: MPI must allow calls from any
  !> thread (MPI_THREAD_MULTIPLE; impact3d itself calls MPI from one thread).
  subroutine par_init()
    integer :: provided
    call MPI_Init_thread(MPI_THREAD_MULTIPLE, provided)
    comm_world = MPI_COMM_WORLD
    call MPI_Comm_rank(comm_world, my_rank)
    call MPI_Comm_size(comm_world, n_ranks)
    ! Collective buffering for the dumps with 4 MiB buffers on the
    ! aggregators (the defaults, 16 to 32 MiB, made the aggregating rank the
    ! largest rank of a run).
    call MPI_Info_create(io_info)
    call MPI_Info_set(io_info, 'cb_buffer_size', '4194304')
  end subroutine par_init

  !> Finish MPI cleanly.
  subroutine par_finalize()
    logical :: done
    call MPI_Finalized(done)
    if (done) return
    if (io_info /= MPI_INFO_NULL) call MPI_Info_free(io_info)
    call MPI_Finalize()
  end subroutine par_finalize

  !> Last resort when a rank cannot reach a collective: message and MPI_Abort.
  subroutine par_abort(message, code)
    character(len=*), intent(in) :: message !< what went wrong
    integer, intent(in) :: code !< non-zero exit code
    write(error_unit, '(a,i0,a)') 'rank ', my_rank, ': '//trim(message)
    flush(error_unit)
    call MPI_Abort(comm_world, max(code, 1))
    error stop 1
  end subroutine par_abort

  !> This rank (0-based).
  integer function par_rank()
    par_rank = my_rank
  end function par_rank

  !> Number of ranks.
  integer function par_size()
    par_size = n_ranks
  end function par_size

  !> The communicator for code in src/parallel.
  function par_comm() result(c)
    type(MPI_Comm) :: c
    c = comm_world
  end function par_comm

  !> The communicator as a plain integer handle (for HDF5's Fortran API).
  integer function par_comm_handle()
    par_comm_handle = comm_world%MPI_VAL
  end function par_comm_handle

  !> The dumps' MPI-IO hints as a plain integer handle (HDF5's Fortran API).
  integer function par_io_info_handle()
    par_io_info_handle = io_info%MPI_VAL
  end function par_io_info_handle

  !> MPI_INFO_NULL as a plain integer handle (for HDF5's Fortran API).
  integer function par_info_null_handle()
    par_info_null_handle = MPI_INFO_NULL%MPI_VAL
  end function par_info_null_handle

  subroutine bcast_int(x)
    integer(ik), intent(inout) :: x
    call MPI_Bcast(x, 1, MPI_INTEGER, 0, comm_world)
  end subroutine bcast_int

  subroutine bcast_int_array(x)
    integer(ik), intent(inout) :: x(:)
    call MPI_Bcast(x, size(x), MPI_INTEGER, 0, comm_world)
  end subroutine bcast_int_array

  subroutine bcast_i8_array(x)
    integer(i8), intent(inout) :: x(:)
    call MPI_Bcast(x, size(x), MPI_INTEGER8, 0, comm_world)
  end subroutine bcast_i8_array

  subroutine bcast_real(x)
    real(rk), intent(inout) :: x
    call MPI_Bcast(x, 1, MPI_DOUBLE_PRECISION, 0, comm_world)
  end subroutine bcast_real

  subroutine bcast_real_array(x)
    real(rk), intent(inout) :: x(:)
    call MPI_Bcast(x, size(x), MPI_DOUBLE_PRECISION, 0, comm_world)
  end subroutine bcast_real_array

  subroutine bcast_real_array2(x)
    real(rk), intent(inout), contiguous :: x(:, :)
    call MPI_Bcast(x, size(x), MPI_DOUBLE_PRECISION, 0, comm_world)
  end subroutine bcast_real_array2

  subroutine bcast_logical(x)
    logical, intent(inout) :: x
    call MPI_Bcast(x, 1, MPI_LOGICAL, 0, comm_world)
  end subroutine bcast_logical

  subroutine bcast_logical_array(x)
    logical, intent(inout) :: x(:)
    call MPI_Bcast(x, size(x), MPI_LOGICAL, 0, comm_world)
  end subroutine bcast_logical_array

  subroutine bcast_string(x)
    character(len=*), intent(inout) :: x
    call MPI_Bcast(x, len(x), MPI_CHARACTER, 0, comm_world)
  end subroutine bcast_string

  subroutine bcast_string_array(x)
    character(len=*), intent(inout) :: x(:)
    call MPI_Bcast(x, len(x) * size(x), MPI_CHARACTER, 0, comm_world)
  end subroutine bcast_string_array

  function sum_real(x, traffic) result(s)
    real(rk), intent(in) :: x
    real(rk) :: s
    type(traffic_t), intent(inout), optional :: traffic
    real(rk) :: t0
    t0 = MPI_Wtime()
    call MPI_Allreduce(x, s, 1, MPI_DOUBLE_PRECISION, MPI_SUM, comm_world)
    if (present(traffic)) call traffic_count(traffic, t0)
  end function sum_real

  !> In-place global sum of a small array (diagnostics only).
  subroutine par_sum_array(x, traffic)
    real(rk), intent(inout) :: x(:)
    real(rk) :: s(size(x))
    type(traffic_t), intent(inout), optional :: traffic
    real(rk) :: t0
    t0 = MPI_Wtime()
    call MPI_Allreduce(x, s, size(x), MPI_DOUBLE_PRECISION, MPI_SUM, comm_world)
    if (present(traffic)) call traffic_count(traffic, t0)
    x = s
  end subroutine par_sum_array

  !> Global sum of each element of a (3, n) array in place (MPI_IN_PLACE:
  !> no second copy of a large array).
  subroutine par_sum_in_place(x)
    real(rk), intent(inout), contiguous :: x(:, :)
    call MPI_Allreduce(MPI_IN_PLACE, x, size(x), MPI_DOUBLE_PRECISION, MPI_SUM, comm_world)
  end subroutine par_sum_in_place

  !> In-place global maximum of each element of a small array.
  subroutine par_max_array(x, traffic)
    real(rk), intent(inout) :: x(:)
    type(traffic_t), intent(inout), optional :: traffic
    real(rk) :: s(size(x)), t0
    t0 = MPI_Wtime()
    call MPI_Allreduce(x, s, size(x), MPI_DOUBLE_PRECISION, MPI_MAX, comm_world)
    if (present(traffic)) call traffic_count(traffic, t0)
    x = s
  end subroutine par_max_array

  !> In-place global exact sums (core_exact_sum): every rank ends with the
  !> sums of all ranks' terms, bitwise the same whatever the rank count and
  !> whichever rank held which terms (an integer reduction of their limbs).
  subroutine par_sum_exact(sums)
    type(exact_sum_t), intent(inout) :: sums(:)
    integer(i8) :: flat(EXACT_PACKED * size(sums)), total(EXACT_PACKED * size(sums))
    call exact_pack(sums, flat)
    call MPI_Allreduce(flat, total, size(flat), MPI_INTEGER8, MPI_SUM, comm_world)
    call exact_unpack(total, sums)
  end subroutine par_sum_exact

  function sum_int(x, traffic) result(s)
    integer(ik), intent(in) :: x
    integer(ik) :: s
    type(traffic_t), intent(inout), optional :: traffic
    real(rk) :: t0
    t0 = MPI_Wtime()
    call MPI_Allreduce(x, s, 1, MPI_INTEGER, MPI_SUM, comm_world)
    if (present(traffic)) call traffic_count(traffic, t0)
  end function sum_int

  function sum_i8(x) result(s)
    integer(i8), intent(in) :: x
    integer(i8) :: s
    call MPI_Allreduce(x, s, 1, MPI_INTEGER8, MPI_SUM, comm_world)
  end function sum_i8

  function min_real(x, traffic) result(s)
    real(rk), intent(in) :: x
    real(rk) :: s
    type(traffic_t), intent(inout), optional :: traffic
    real(rk) :: t0
    t0 = MPI_Wtime()
    call MPI_Allreduce(x, s, 1, MPI_DOUBLE_PRECISION, MPI_MIN, comm_world)
    if (present(traffic)) call traffic_count(traffic, t0)
  end function min_real

  function min_int(x, traffic) result(s)
    integer(ik), intent(in) :: x
    integer(ik) :: s
    type(traffic_t), intent(inout), optional :: traffic
    real(rk) :: t0
    t0 = MPI_Wtime()
    call MPI_Allreduce(x, s, 1, MPI_INTEGER, MPI_MIN, comm_world)
    if (present(traffic)) call traffic_count(traffic, t0)
  end function min_int

  function max_real(x, traffic) result(s)
    real(rk), intent(in) :: x
    real(rk) :: s
    type(traffic_t), intent(inout), optional :: traffic
    real(rk) :: t0
    t0 = MPI_Wtime()
    call MPI_Allreduce(x, s, 1, MPI_DOUBLE_PRECISION, MPI_MAX, comm_world)
    if (present(traffic)) call traffic_count(traffic, t0)
  end function max_real

  function max_int(x, traffic) result(s)
    integer(ik), intent(in) :: x
    integer(ik) :: s
    type(traffic_t), intent(inout), optional :: traffic
    real(rk) :: t0
    t0 = MPI_Wtime()
    call MPI_Allreduce(x, s, 1, MPI_INTEGER, MPI_MAX, comm_world)
    if (present(traffic)) call traffic_count(traffic, t0)
  end function max_int

  !> One collective call into traffic, with the time since t0.
  subroutine traffic_count(traffic, t0)
    type(traffic_t), intent(inout) :: traffic
    real(rk), intent(in) :: t0 !< MPI_Wtime before the call
    if (n_ranks == 1) return
    traffic%collectives = traffic%collectives + 1
    traffic%wait_seconds = traffic%wait_seconds + (MPI_Wtime() - t0)
  end subroutine traffic_count

  !> all(:, r+1) = record of rank r.
  subroutine allgather_real(record, all, traffic)
    real(rk), intent(in) :: record(:)
    real(rk), intent(out) :: all(:, :)
    type(traffic_t), intent(inout), optional :: traffic
    real(rk) :: t0
    t0 = MPI_Wtime()
    call MPI_Allgather(record, size(record), MPI_DOUBLE_PRECISION, all, size(record), &
        MPI_DOUBLE_PRECISION, comm_world)
    if (present(traffic)) call traffic_count(traffic, t0)
  end subroutine allgather_real

  !> all(:, r+1) = record of rank r.
  subroutine allgather_int(record, all, traffic)
    integer(ik), intent(in) :: record(:)
    integer(ik), intent(out) :: all(:, :)
    type(traffic_t), intent(inout), optional :: traffic
    real(rk) :: t0
    t0 = MPI_Wtime()
    call MPI_Allgather(record, size(record), MPI_INTEGER, all, size(record), &
        MPI_INTEGER, comm_world)
    if (present(traffic)) call traffic_count(traffic, t0)
  end subroutine allgather_int

  !> all(:, r+1) = record of rank r (64-bit integers: global ids).
  subroutine allgather_i8(record, all)
    integer(i8), intent(in) :: record(:)
    integer(i8), intent(out) :: all(:, :)
    call MPI_Allgather(record, size(record), MPI_INTEGER8, all, size(record), &
        MPI_INTEGER8, comm_world)
  end subroutine allgather_i8

end module parallel_env
